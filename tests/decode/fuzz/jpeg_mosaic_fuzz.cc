// Fuzz target: greyscale JPEG mosaics (ReadJpegCoefficients, and RestoreJpegMosaic on what it returns for small
// images: the restoration's cost grows with the image, not with what the bytes say).

#include "../../core/fuzz/fuzz_file.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/jpeg_mosaic.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto coefficients = lfsp::decode::ReadJpegCoefficients(FuzzInputFile(data, size, ".jpg"));
    if (coefficients && coefficients->blocks_x * coefficients->blocks_y <= 64 * 64) {
      lfsp::decode::MosaicRestoreOptions options;
      options.iterations = 2;
      (void)lfsp::decode::RestoreJpegMosaic(*coefficients, options);
    }
  } catch (const lfsp::Error&) {
  }
  return 0;
}
