// Fuzz target: plain raw images (ReadPlainRawImage: a Bayer mosaic in a PNG, TIFF or JPEG without Lytro metadata,
// `lfsp decode IMAGE --camera ...`). The first byte chooses the file's extension (which decides whether a greyscale
// JPEG's mosaic is restored) and the options a command line would give; the rest is the image file:
//   bits 0-1  extension: .png .tif .jpg .tiff
//   bits 2-3  --camera: none, f01, illum, none
//   bit 4     --jpeg-grey scene (refused without a camera)
//   bit 5     --bayer rggb
//   bits 6-7  levels: the defaults, --black 16 --white 200, --white 4000, --black 300 --white 100 (refused)
// The restoration runs 2 iterations (the jpeg_mosaic target covers it). Bad input must end in lfsp::Error; any other
// exception or a crash is a bug.

#include "../../core/fuzz/fuzz_file.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/raw_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t choice = data[0];
  static const char* const kExtensions[] = {".png", ".tif", ".jpg", ".tiff"};
  static const char* const kCameras[] = {"", "f01", "illum", ""};
  lfsp::decode::PlainRawOptions options;
  options.camera = kCameras[(choice >> 2) & 3];
  options.jpeg_grey = (choice & 0x10) != 0 ? lfsp::decode::JpegGrey::kScene : lfsp::decode::JpegGrey::kSensor;
  if ((choice & 0x20) != 0) options.bayer = lfsp::decode::BayerPattern::kRGGB;
  switch (choice >> 6) {
    case 1:
      options.black = 16.0;
      options.white = 200.0;
      break;
    case 2:
      options.white = 4000.0;
      break;
    case 3:
      options.black = 300.0;
      options.white = 100.0;
      break;
    default:
      break;
  }
  options.jpeg_restore_iterations = 2;
  try {
    (void)lfsp::decode::ReadPlainRawImage(FuzzInputFile(data + 1, size - 1, kExtensions[choice & 3]), options);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
