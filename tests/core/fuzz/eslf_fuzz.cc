// Fuzz target: ESLF light-field images (one PNG holding every view's pixels interleaved, ReadEslf), with the
// angular size taken from the image as a user's file would give it.

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/eslf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::ReadEslf(FuzzInputFile(data, size, ".png"));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
