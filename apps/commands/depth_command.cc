// `lfsp depth LF --out DISP.pfm`: occlusion-aware centre-view disparity of a light field (views folder or .h5
// bundle). Writes DISP.pfm, DISP.png (colour-mapped preview), DISP_confidence.pfm and DISP.summary.json; when the
// input carries a ground-truth disparity (HCI gt_disp_lowres.pfm beside the views, or the bundle's dataset), the
// summary also holds the HCI metrics against it.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

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
  std::optional<float> dmin;
  std::optional<float> dmax;
  bool no_occlusion = false;
  bool winner_take_all = false;
  depth::DepthOptions method;
};

depth::DepthOptions MethodOptions(const DepthCommandOptions& options) {
  depth::DepthOptions method = options.method;
  if (options.dmin.has_value() != options.dmax.has_value()) throw Error("lfsp depth: give both --dmin and --dmax");
  if (options.dmin) method.range = DisparityRange{*options.dmin, *options.dmax};
  if (options.no_occlusion) method.occlusion_handling = false;
  if (options.winner_take_all) method.regularise = false;
  return method;
}

void RunDepth(const DepthCommandOptions& options) {
  const depth::DepthOptions method = MethodOptions(options);
  const Stopwatch stopwatch;
  Bundle bundle = LoadInput(options.input);
  nlohmann::ordered_json summary = {{"command", "depth"}, {"input", options.input}};
  summary["views"] = SelectViews(bundle, options.views, options.input);
  summary["load_seconds"] = stopwatch.Seconds();
  spdlog::info("{}: {}", options.input, ToString(bundle.light_field.shape()));
  stages::RunDepthStage(bundle, method, options.output, std::move(summary));
  spdlog::info("wrote {} ({:.2f} s)", options.output, stopwatch.Seconds());
}

void AddDepthCommand(CLI::App& parent) {
  auto options = std::make_shared<DepthCommandOptions>();
  depth::DepthOptions& method = options->method;
  CLI::App* command = parent.add_subcommand(
      "depth",
      "Occlusion-aware centre-view disparity (cost volume with edge-split angular patches, semi-global "
      "aggregation, sub-label refinement); writes DISP.pfm, DISP.png, DISP_confidence.pfm, DISP.summary.json");
  command->add_option("input", options->input, "Light field: views folder (HCI style) or .h5 bundle")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--out", options->output, "Output disparity PFM (HCI convention)")->required();
  AddViewsOption(command, options->views);
  command->add_option(
      "--dmin", options->dmin,
      "Smallest disparity (px per view step); default: disp_min of parameters.cfg / bundle metadata, else "
      "estimated from the views (a coarse sweep, logged)");
  command->add_option("--dmax", options->dmax, "Largest disparity; default: disp_max of the metadata, else estimated");
  command->add_option("--labels", method.labels, "Number of disparity labels")
      ->capture_default_str()
      ->check(CLI::Range(3, 1024));
  command->add_flag("--no-occlusion", options->no_occlusion,
                    "Use all views everywhere (no edge-split of the angular patch); default: off");
  command->add_flag("--wta", options->winner_take_all,
                    "Plain winner-take-all on the cost volume: no aggregation, no median (baseline); default: off");
  command->add_flag("--plane-fit", method.plane_fit,
                    "Slanted-plane refinement of textureless pixels per superpixel (antinous: BadPix 0.07 5.9 -> "
                    "5.0 %, but worse on thin occluders); default: off");
  command
      ->add_option("--occlusion-radius", method.occlusion.radius,
                   "Pixels within this distance of a centre-view edge use the better half of the views; 0 = "
                   "automatic (half the largest shift across the angular patch over the disparity range)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--p1", method.sgm.p1, "SGM penalty for a one-label step")->capture_default_str();
  command->add_option("--p2", method.sgm.p2, "SGM penalty for a larger jump (lowered across colour edges)")
      ->capture_default_str();
  command
      ->add_option("--excluded-ring", method.cost.excluded_ring,
                   "Leave the views within N steps of the centre out of the cost; -1 = automatic (1 for light "
                   "fields decoded from a lenslet capture, whose neighbouring views share sensor pixels and noise)")
      ->capture_default_str()
      ->check(CLI::Range(-1, 16));
  command->add_option("--colour-weight", method.cost.colour_weight, "Weight of the colour term of the cost")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--detail-weight", method.cost.detail_weight,
                   "Weight of the detail term of the cost (the locally normalised high-pass grey image); -1 = "
                   "automatic: 1 on views that are not presmoothed, else the band's signal against its noise, "
                   "m^2 / (m^2 + (16 n)^2), m the median local RMS of the centre view's detail, n the noise floor's "
                   "share of it (0.15-0.2 on full-size lenslet decodes with weak texture)")
      ->capture_default_str()
      ->check(CLI::Range(-1.0, 100.0));
  command
      ->add_option("--presmooth", method.presmooth_sigma,
                   "Gaussian smoothing of every view before matching, pixels; -1 = automatic from the estimated noise "
                   "(none on clean views, up to 2.5 px in low light), 0 = off")
      ->capture_default_str()
      ->check(CLI::Range(-1.0, 10.0));
  command->add_option("--median-radius", method.median_radius, "Weighted-median refinement radius (0 = off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->callback([options] { RunDepth(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(70, "depth", AddDepthCommand);

}  // namespace lfsp::cli
