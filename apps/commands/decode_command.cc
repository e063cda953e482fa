// `lfsp decode CAPTURE [--white-images DIR] --out OUT`: a Lytro raw capture to a 4D light field.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/capture_decoder.h"
#include "raw_input_options.h"
#include "stages/decode_stage.h"

namespace lfsp::cli {
namespace {

struct DecodeCommandOptions {
  std::string capture;
  std::string white_images;
  std::string out;
  std::string demosaic = "gradient";
  std::string colour = "camera";
  bool no_hot_pixels = false;
  double dehex = 0.1;
  int bit_depth = 16;
  bool no_white_image = false;
  PlainRawArguments plain;
};

void RunDecode(const DecodeCommandOptions& options) {
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth must be 8 or 16");
  decode::CaptureDecodeOptions decode_options;
  decode_options.white_images = options.white_images;
  decode_options.no_white_image = options.no_white_image;
  decode_options.plain = ToPlainRawOptions(options.plain);
  decode_options.decode.demosaic = decode::DemosaicMethodFromString(options.demosaic);
  decode_options.decode.colour = decode::ColourModeFromString(options.colour);
  decode_options.decode.correct_hot_pixels = !options.no_hot_pixels;
  if (!(options.dehex >= 0.0 && options.dehex <= 0.25)) throw Error("--dehex must be in [0, 0.25]");
  decode_options.decode.dehex = options.dehex;

  const nlohmann::json parameters = {{"parameters",
                                      {{"demosaic", options.demosaic},
                                       {"colour", options.colour},
                                       {"hot_pixels", !options.no_hot_pixels},
                                       {"dehex", options.dehex},
                                       {"bit_depth", options.bit_depth}}}};
  const stages::DecodeStageResult result =
      stages::RunDecodeStage(options.capture, decode_options, options.out, options.bit_depth, parameters);
  const nlohmann::json& lf = result.summary.at("light_field");
  std::printf("%s: %dx%d views of %dx%d -> %s\nwhite image: %s\n", options.capture.c_str(), lf.at("nu").get<int>(),
              lf.at("nv").get<int>(), lf.at("width").get<int>(), lf.at("height").get<int>(), options.out.c_str(),
              result.summary.at("white_image").at("why").get<std::string>().c_str());
}

void AddDecodeCommand(CLI::App& app) {
  auto options = std::make_shared<DecodeCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "decode",
      "Decode a Lytro raw capture (.lfp/.lfr/.LFR, .RAW + .TXT/.json, or a plain raw PNG/TIFF/JPEG with --camera) "
      "into a 4D light field: white image by serial/zoom/focus (or estimated from the capture), lenslet grid fit, "
      "hot pixels, devignetting, demosaic, hex->rect slicing, colour");
  command->add_option("capture", options->capture, "The capture file")->required();
  command->add_option("--white-images", options->white_images,
                      "Folder of white images, MOD_*.RAW + .TXT or calibration archives data.C.* (default: the "
                      "capture's folder, searched recursively, so its whites/ sub-folder is found)");
  command
      ->add_option("--out", options->out,
                   "Output: OUT.h5 writes a bundle, OUT.png an ESLF image, anything else a views folder")
      ->required();
  command->add_flag("--no-white-image", options->no_white_image,
                    "Estimate the white image (micro-image vignetting) and the lenslet grid from the capture itself "
                    "instead of looking one up (automatic, with a warning, when no white image matches; always for "
                    "plain raw images)");
  AddPlainRawOptions(command, options->plain);
  command->add_option("--demosaic", options->demosaic, "gradient | edge-aware | bilinear (default: gradient)");
  command->add_option("--colour", options->colour,
                      "camera (white balance, colour matrix, exposure bias, sRGB) | linear (devignetted scene-linear "
                      "RGB) (default: camera)");
  command->add_flag("--no-hot-pixels", options->no_hot_pixels, "Skip hot-pixel correction (default: corrected)");
  command->add_option("--dehex", options->dehex,
                      "Row-alternation softening against hexagonal artefacts, 0..0.25 (default: 0.1)");
  command->add_option("--bit-depth", options->bit_depth, "Views folder PNG bit depth, 8 or 16 (default: 16)");
  command->callback([options] { RunDecode(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(40, "decode", AddDecodeCommand);

}  // namespace lfsp::cli
