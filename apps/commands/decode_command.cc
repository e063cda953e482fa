// `lfsp decode CAPTURE --out OUT`: a Lytro raw capture to a 4D light field.
//
// For now this opens and checks the capture (container, SHA-1s, metadata, raw buffer size) and fails cleanly on
// files that cannot be decoded, such as Lytro Desktop exports that hold only a focus stack or depth map. The
// decoding pipeline itself (white image, grid model, demosaic, slicing) is not written yet.

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lytro_capture.h"

namespace lfsp::cli {
namespace {

struct DecodeOptions {
  std::string capture;
  std::string white_images;
  std::string out;
};

void RunDecode(const DecodeOptions& options) {
  const decode::LytroCapture capture = decode::OpenLytroCapture(options.capture);
  // RawBytes() throws "<file>: no raw image: this file holds ..." for focus-stack / depth exports.
  (void)capture.RawBytes();
  if (capture.IsWhiteImage()) {
    throw Error(options.capture +
                ": this is a white (modulation) image, not a capture; index it with "
                "`lfsp whites build` instead");
  }
  const decode::RawImage raw = capture.ReadRawImage();  // checks the metadata and the buffer size
  throw Error(options.capture + ": the raw image (" + std::to_string(raw.width) + "x" + std::to_string(raw.height) +
              ") reads correctly, but decoding to a light field is not implemented yet in this build");
}

void AddDecodeCommand(CLI::App& app) {
  auto options = std::make_shared<DecodeOptions>();
  CLI::App* command = app.add_subcommand(
      "decode", "Decode a Lytro raw capture (.lfp/.lfr/.LFR, or .RAW + .TXT/.json) into a 4D light field");
  command->add_option("capture", options->capture, "The capture file")->required();
  command->add_option("--white-images", options->white_images,
                      "Folder of white images (default: the capture's folder and its whites/ sub-folder)");
  command->add_option("--out", options->out, "Output: a .h5 bundle or a views folder")->required();
  command->callback([options] { RunDecode(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(40, "decode", AddDecodeCommand);

}  // namespace lfsp::cli
