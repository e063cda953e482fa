// Fuzz target: calibration files (ReadCalibration: JSON, then the fields, the 5x5 matrix and its inverse).

#include "../../core/fuzz/fuzz_file.h"
#include "../../decode/fuzz/fuzz_target.h"
#include "lfsp/calibrate/calibration_io.h"
#include "lfsp/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::calibrate::ReadCalibration(FuzzInputFile(data, size, ".json"));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
