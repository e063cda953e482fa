// `lfsp depth LF --out DISP.pfm`: occlusion-aware centre-view disparity of a light field (views folder or .h5
// bundle). Writes DISP.pfm, DISP.png (colour-mapped preview), DISP_confidence.pfm and DISP.summary.json; when the
// input carries a ground-truth disparity (HCI gt_disp_lowres.pfm beside the views, or the bundle's dataset), the
// summary also holds the HCI metrics against it.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "arguments/depth_arguments.h"
#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/depth/depth_estimator.h"
#include "stages/depth_stage.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

struct DepthCommandOptions {
  int views = 0;
  std::string input;
  std::string output;
  DepthArguments method;
};

void RunDepth(const DepthCommandOptions& options) {
  const depth::DepthOptions method = ToDepthOptions(options.method);
  const Stopwatch stopwatch;
  nlohmann::json views;
  Bundle bundle = LoadSelectedViews(options.input, options.views, views);
  nlohmann::ordered_json summary = {{"command", "depth"}, {"input", options.input}};
  summary["views"] = views;
  summary["load_seconds"] = stopwatch.Seconds();
  spdlog::info("{}: {}", options.input, ToString(bundle.light_field.shape()));
  stages::RunDepthStage(bundle, method, options.output, std::move(summary));
  spdlog::info("wrote {} ({:.2f} s)", options.output, stopwatch.Seconds());
}

void AddDepthCommand(CLI::App& parent) {
  auto options = std::make_shared<DepthCommandOptions>();
  CLI::App* command = parent.add_subcommand(
      "depth",
      "Occlusion-aware centre-view disparity (cost volume with edge-split angular patches, semi-global "
      "aggregation, sub-label refinement); writes DISP.pfm, DISP.png, DISP_confidence.pfm, DISP.summary.json");
  command->add_option("input", options->input, "Light field: views folder (HCI style) or .h5 bundle")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--out", options->output, "Output disparity PFM (HCI convention)")->required();
  AddViewsOption(command, options->views);
  AddDepthArguments(command, options->method);
  command->callback([options] { RunDepth(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(70, "depth", AddDepthCommand);

}  // namespace lfsp::cli
