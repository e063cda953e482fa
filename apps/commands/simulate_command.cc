// `lfsp simulate`: a synthetic scene rendered as an ideal light field or as a Lytro lenslet capture (container,
// white images) with its ground truth. A thin layer over lfsp::simulate::Simulate().

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "arguments/simulate_arguments.h"
#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/simulate/scene.h"
#include "lfsp/simulate/simulate.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct SimulateCommandOptions {
  SimulateArguments rendering;
  std::string out;
  bool list_scenes = false;
};

void RunSimulate(const SimulateCommandOptions& options) {
  if (options.list_scenes) {
    for (const auto& name : simulate::BuiltinSceneNames())
      std::printf("%-13s %s\n", name.c_str(), simulate::BuiltinScene(name).description.c_str());
    return;
  }
  if (options.out.empty()) throw Error("--out: required (the output folder)");
  const simulate::SimulateOptions library = ToSimulateOptions(options.rendering);
  const simulate::SimulateResult result = simulate::Simulate(library, options.out);
  nlohmann::json summary = result.summary;
  summary["out"] = options.out;
  summary["camera_option"] = library.camera;
  stages::WriteJsonSummary(summary, stages::SummaryPathFor(options.out));
  for (const auto& file : result.files) std::printf("%s\n", (std::filesystem::path(options.out) / file).c_str());
}

void AddSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<SimulateCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Render a synthetic scene as a Lytro lenslet capture (container + white images) or an ideal light field, "
      "with ground truth (disparity, labels, lenslet geometry)");
  AddSimulateArguments(command, options->rendering);
  command->add_flag("--list-scenes", options->list_scenes, "List the built-in scenes and exit");
  command->add_option("--out", options->out, "Output folder (created if needed)");
  command->callback([options] { RunSimulate(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(20, "simulate", AddSimulateCommand);

}  // namespace lfsp::cli
