// `lfsp decode CAPTURE [--white-images DIR] --out OUT`: a Lytro raw capture to a 4D light field.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "arguments/decode_arguments.h"
#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/capture_decoder.h"
#include "stages/decode_stage.h"

namespace lfsp::cli {
namespace {

struct DecodeCommandOptions {
  std::string capture;
  std::string out;
  int bit_depth = 16;
  DecodeArguments decode;
};

void RunDecode(const DecodeCommandOptions& options) {
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth must be 8 or 16");
  const decode::CaptureDecodeOptions decode_options = ToCaptureDecodeOptions(options.decode);
  nlohmann::json parameters = {{"parameters", DecodeParameters(options.decode)}};
  parameters["parameters"]["bit_depth"] = options.bit_depth;
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
  command
      ->add_option("--out", options->out,
                   "Output: OUT.h5 writes a bundle, OUT.png an ESLF image, anything else a views folder")
      ->required();
  AddDecodeArguments(command, options->decode);
  command->add_option("--bit-depth", options->bit_depth, "Views folder PNG bit depth, 8 or 16 (default: 16)");
  command->callback([options] { RunDecode(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(40, "decode", AddDecodeCommand);

}  // namespace lfsp::cli
