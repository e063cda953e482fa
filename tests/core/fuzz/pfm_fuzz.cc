// Fuzz target: PFM disparity maps (ReadPfm).

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/pfm.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::ReadPfm(FuzzInputFile(data, size, ".pfm"));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
