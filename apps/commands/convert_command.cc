// `lfsp convert IN OUT`: a light field from any format lfsp reads to any it writes (views folder in any naming,
// .h5 bundle, ESLF .png, MATLAB .mat) - for instance a views folder from another tool to LFToolbox's .mat for MATLAB
// - or to an animation of its views (.gif, .mp4); a PFM disparity map to a 16-bit PNG.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cctype>
#include <filesystem>
#include <memory>
#include <string>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/file_names.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/visualize.h"

namespace lfsp::cli {
namespace {

struct ConvertCommandOptions {
  std::string input;
  std::string out;
  int bit_depth = 16;
  std::string view_format = "png";
  double fps = 8.0;
};

void RunConvert(const ConvertCommandOptions& options) {
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth: expected 8 or 16");
  if (options.view_format != "png" && options.view_format != "tif")
    throw Error("--view-format: expected png or tif, not " + options.view_format);
  if (!(options.fps > 0.0 && options.fps <= 120.0)) throw Error("--fps: expected a rate in (0, 120]");
  const std::string out_extension = LowerExtension(options.out);
  if (LowerExtension(options.input) == ".pfm") {
    const DisparityMap disparity = ReadPfm(options.input);
    if (out_extension == ".png") {
      WriteDisparityPng16(disparity, options.out);
    } else if (out_extension == ".pfm") {
      WritePfm(disparity, options.out);
    } else {
      throw Error(options.out + ": a disparity map converts to .png (16-bit, range in its text chunks) or .pfm");
    }
    spdlog::info("{}: disparity {}x{} -> {}", options.input, disparity.width(), disparity.height(), options.out);
    return;
  }
  const Bundle bundle = LoadInput(options.input);
  if (out_extension == ".gif" || out_extension == ".mp4") {
    WriteAnimation(ViewSweepFrames(bundle.light_field), options.out, options.fps);
  } else if (out_extension == ".pfm") {
    // The disparity a bundle or folder carries (e.g. a simulation's ground truth), in the HCI convention.
    if (!bundle.disparity) throw Error(options.input + ": holds no disparity map to write as " + options.out);
    WritePfm(*bundle.disparity, options.out);
    spdlog::info("{}: disparity {}x{} -> {}", options.input, bundle.disparity->width(), bundle.disparity->height(),
                 options.out);
    return;
  } else {
    SaveLightField(bundle, options.out, options.bit_depth, "." + options.view_format);
  }
  spdlog::info("{}: {} -> {}", options.input, ToString(bundle.light_field.shape()), options.out);
}

void AddConvertCommand(CLI::App& app) {
  auto options = std::make_shared<ConvertCommandOptions>();
  CLI::App* command =
      app.add_subcommand("convert",
                         "Write a light field in another format: views folder, .h5 bundle, ESLF .png or MATLAB .mat "
                         "(LFToolbox's LF(v,u,y,x,c) with the weight channel), chosen by the output's name");
  command
      ->add_option("input", options->input,
                   "Light field: views folder (any naming), .h5, ESLF .png or .mat; or a disparity .pfm")
      ->required()
      ->check(CLI::ExistingPath);
  command
      ->add_option(
          "output", options->out,
          "OUT.h5 a bundle, OUT.png an ESLF image, OUT.mat LFToolbox's layout, OUT.gif / OUT.mp4 an animation of "
          "the views, OUT.pfm the disparity map the input carries, anything else a views folder (names "
          "ending in another file type's extension, such as .jpg, are refused)")
      ->required();
  command->add_option("--bit-depth", options->bit_depth, "Bits per sample of PNG/TIFF outputs: 8 or 16 (default: 16)");
  command->add_option("--view-format", options->view_format,
                      "File type of a views folder's views: png or tif (default: png)");
  command->add_option("--fps", options->fps, "Frames per second of a .gif/.mp4 (default: 8)");
  command->callback([options] { RunConvert(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(45, "convert", AddConvertCommand);

}  // namespace lfsp::cli
