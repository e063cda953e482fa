#include "raw_input_options.h"

#include "lfsp/core/error.h"

namespace lfsp::cli {

void AddPlainRawOptions(CLI::App* command, PlainRawArguments& arguments) {
  command->add_option("--camera", arguments.camera,
                      "Plain raw images: the camera, f01 | illum (sensor layout, levels, micro-lens pitch, colour; "
                      "Lytro files carry their own)");
  command->add_option("--bayer", arguments.bayer,
                      "Plain raw images: Bayer pattern of the top-left 2x2 tile, rggb | grbg | gbrg | bggr "
                      "(default: the camera's; F01 bggr, Illum grbg)");
  command->add_option("--black", arguments.black,
                      "Plain raw images: black level in file codes (default with --camera: the camera's, scaled to "
                      "the file's range unless a 16-bit file fits under the camera's white level (a sensor dump): "
                      "F01 10.46 of 255; without --camera: 0)");
  command->add_option("--white", arguments.white,
                      "Plain raw images: white (saturation) level in file codes (default: 255 / 65535, or the "
                      "camera's for a 16-bit sensor dump)");
  command
      ->add_option("--jpeg-restore", arguments.jpeg_restore,
                   "Greyscale JPEG mosaics: iterations restoring the Bayer colour that JPEG quantization took, from "
                   "the file's DCT coefficients (colour bands otherwise); 0 = the plain JPEG decode")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
  command
      ->add_option(
          "--jpeg-grey", arguments.jpeg_grey,
          "Greyscale JPEG mosaics with --camera: the colour the restoration fills in where the JPEG kept "
          "none, and smooths towards. sensor: a flat mosaic (magenta under daylight gains). scene: the automatic "
          "white balance of a short first restoration (0.2-1 s more on an F01 frame), whatever "
          "--white-balance says; --white-balance auto (the default for plain images) then applies the same "
          "gains. Lowers the real F01 frames' colour bands but blurs fine colour and raises the simulated "
          "leaves capture's bands. No effect with --jpeg-restore 0 (README, Plain raw images)")
      ->capture_default_str()
      ->check(CLI::IsMember({"sensor", "scene"}));
}

decode::PlainRawOptions ToPlainRawOptions(const PlainRawArguments& arguments) {
  decode::PlainRawOptions options;
  if (!arguments.camera.empty()) {
    if (arguments.camera != "f01" && arguments.camera != "illum")
      throw Error("--camera '" + arguments.camera + "': unknown (expected f01 or illum)");
    options.camera = arguments.camera;
  }
  if (!arguments.bayer.empty()) options.bayer = decode::BayerPatternFromString(arguments.bayer);
  if (arguments.black >= 0.0) options.black = arguments.black;
  if (arguments.white >= 0.0) options.white = arguments.white;
  options.jpeg_restore_iterations = arguments.jpeg_restore;
  options.jpeg_grey = decode::JpegGreyFromString(arguments.jpeg_grey);
  return options;
}

}  // namespace lfsp::cli
