// Fuzz target: MATLAB .mat light fields, v5 through libmatio and v7.3 through HDF5 (ReadMatLightField).

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/mat_light_field.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::ReadMatLightField(FuzzInputFile(data, size, ".mat"));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
