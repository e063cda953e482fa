// Fuzz target: view images (ReadImage: the PNG chunk walk, declared-size checks, then OpenImageIO).

#include "../../decode/fuzz/fuzz_target.h"
#include "fuzz_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::ReadImage(FuzzInputFile(data, size, ".png"));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
