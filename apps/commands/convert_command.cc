// `lfsp convert IN OUT`: a light field from any format lfsp reads to any it writes (views folder in any naming,
// .h5 bundle, ESLF .png, MATLAB .mat) - for instance a views folder from another tool to LFToolbox's .mat for MATLAB.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"

namespace lfsp::cli {
namespace {

struct ConvertCommandOptions {
  std::string input;
  std::string out;
  int bit_depth = 16;
};

void RunConvert(const ConvertCommandOptions& options) {
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth: expected 8 or 16");
  const Bundle bundle = LoadInput(options.input);
  SaveLightField(bundle, options.out, options.bit_depth);
  spdlog::info("{}: {} -> {}", options.input, ToString(bundle.light_field.shape()), options.out);
}

void AddConvertCommand(CLI::App& app) {
  auto options = std::make_shared<ConvertCommandOptions>();
  CLI::App* command =
      app.add_subcommand("convert",
                         "Write a light field in another format: views folder, .h5 bundle, ESLF .png or MATLAB .mat "
                         "(LFToolbox's LF(v,u,y,x,c) with the weight channel), chosen by the output's name");
  command->add_option("input", options->input, "Light field: views folder (any naming), .h5, ESLF .png or .mat")
      ->required()
      ->check(CLI::ExistingPath);
  command
      ->add_option("output", options->out,
                   "OUT.h5 a bundle, OUT.png an ESLF image, OUT.mat LFToolbox's layout, anything else a views folder")
      ->required();
  command->add_option("--bit-depth", options->bit_depth, "Bits per sample of PNG outputs: 8 or 16 (default: 16)");
  command->callback([options] { RunConvert(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(45, "convert", AddConvertCommand);

}  // namespace lfsp::cli
