// `lfsp segment LF --disparity DISP.pfm --out OUT.h5`: light-field superpixels (LFSP) of a light field (views folder
// or .h5 bundle) given a centre-view disparity. Writes OUT.h5 (the light field, the disparity used and `labels`
// nv x nu x H x W), OUT.planes.json (one slanted plane per label), boundary overlays of the centre view and of a
// horizontal and a vertical EPI (OUT.overlay_centre.png, OUT.overlay_epi_h.png, OUT.overlay_epi_v.png),
// optionally 16-bit label PNGs per view, and OUT.summary.json.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "arguments/segment_arguments.h"
#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/segment/lfsp.h"
#include "stages/segment_stage.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

struct SegmentCommandOptions {
  int views = 0;
  std::string input;
  std::string disparity;
  std::string output;
  std::string labels_png;
  int epi_row = -1;
  int epi_column = -1;
  segment::LfspParams params;
};

void RunSegment(const SegmentCommandOptions& options) {
  const Stopwatch stopwatch;
  nlohmann::json views;
  Bundle bundle = LoadSelectedViews(options.input, options.views, views);
  nlohmann::ordered_json summary = {{"command", "segment"}, {"input", options.input}};
  summary["views"] = views;
  DisparityMap disparity;
  std::string disparity_source;
  if (!options.disparity.empty()) {
    disparity = ReadPfm(options.disparity);
    disparity_source = options.disparity;
  } else if (bundle.disparity) {
    disparity = *bundle.disparity;
    disparity_source = options.input + " (its own disparity)";
  } else {
    throw Error(options.input + ": no disparity in the input; give --disparity DISP.pfm");
  }
  summary["load_seconds"] = stopwatch.Seconds();
  spdlog::info("{}: {}, disparity from {}", options.input, ToString(bundle.light_field.shape()), disparity_source);
  stages::SegmentStageOptions stage;
  stage.params = options.params;
  stage.epi_row = options.epi_row;
  stage.epi_column = options.epi_column;
  stage.labels_png = options.labels_png;
  stages::RunSegmentStage(bundle.light_field, disparity, disparity_source, stage, options.output, std::move(summary));
  spdlog::info("wrote {} ({:.2f} s)", options.output, stopwatch.Seconds());
}

void AddSegmentCommand(CLI::App& parent) {
  auto options = std::make_shared<SegmentCommandOptions>();
  CLI::App* command = parent.add_subcommand(
      "segment",
      "Light-field superpixels (LFSP, Zhu et al. TIP 2020): consistent labels for every ray of every view; writes "
      "OUT.h5 (labels nv x nu x H x W), OUT.planes.json, boundary overlays (centre view, EPIs), OUT.summary.json");
  command->add_option("input", options->input, "Light field: views folder (HCI style) or .h5 bundle")
      ->required()
      ->check(CLI::ExistingPath);
  command
      ->add_option("--disparity", options->disparity,
                   "Centre-view disparity (PFM, HCI convention); default: the input's own (gt_disp_lowres.pfm "
                   "beside the views, or the bundle's dataset)")
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->output, "Output bundle (.h5)")->required();
  AddViewsOption(command, options->views);
  command->add_option("--labels-png", options->labels_png,
                      "Also write label_Cam%03d.png (16-bit, one per view) into this folder (default: none)");
  command->add_option("--epi-row", options->epi_row, "Image row of the horizontal EPI overlay (default: middle)");
  command->add_option("--epi-column", options->epi_column,
                      "Image column of the vertical EPI overlay (default: middle)");
  AddLfspParameters(command, options->params);
  command->callback([options] {
    segment::Validate(options->params);
    RunSegment(*options);
  });
}

}  // namespace

LFSP_REGISTER_COMMAND(80, "segment", AddSegmentCommand);

}  // namespace lfsp::cli
