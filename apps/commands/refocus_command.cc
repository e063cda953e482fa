// `lfsp refocus LF --out DIR`: shift-and-sum refocused images (a focal stack), an all-in-focus image from a
// disparity map, and the sheared light field at a refocus level.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "arguments/refocus_arguments.h"
#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/stats.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/edit/refocus.h"
#include "stages/refocus_stage.h"
#include "view_selection.h"

namespace lfsp::cli {
namespace {

namespace fs = std::filesystem;

struct RefocusCommandOptions {
  int views = 0;
  std::string input;
  std::vector<float> disparities;
  int stack = 0;
  std::vector<float> range;
  bool all_in_focus = false;
  std::string disparity_path;
  bool no_occlusion = false;
  std::optional<float> shear;
  std::string out_lf;
  RefocusArguments resampling;
  int bit_depth = 8;
  std::string out;
};

// The range a --stack spans: --range, else the light field's recorded disparity range (HCI parameters.cfg), else
// the finite range of its disparity map.
std::pair<float, float> StackRange(const RefocusCommandOptions& options, const Bundle& bundle) {
  if (!options.range.empty()) {
    if (options.range.size() != 2) throw Error("--range: expected MIN,MAX");
    return {options.range[0], options.range[1]};
  }
  if (const auto range = DisparityRangeFromMetadata(bundle.light_field.metadata)) return {range->min, range->max};
  if (bundle.disparity) {
    const ValueStats stats = DisparityStats(*bundle.disparity);
    if (stats.count > 0) return {static_cast<float>(stats.min), static_cast<float>(stats.max)};
  }
  throw Error("--stack: " + options.input +
              " records no disparity range and has no disparity map; give --range MIN,MAX or --disparities");
}

constexpr int kMaxStack = 1000;

void ValidateOptions(const RefocusCommandOptions& options) {
  if (options.stack < 0 || options.stack > kMaxStack)
    throw Error("--stack: expected a number of slices in 1.." + std::to_string(kMaxStack));
  for (const float d : options.disparities) RequireRefocusDisparity(d, "--disparities");
  for (const float d : options.range) RequireRefocusDisparity(d, "--range");
  if (options.shear) RequireRefocusDisparity(*options.shear, "--shear");
  if (!options.disparities.empty() && options.stack > 0) throw Error("give either --disparities or --stack, not both");
  if (options.shear.has_value() != !options.out_lf.empty())
    throw Error("--shear S and --out-lf OUT go together: give both or neither");
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth: expected 8 or 16");
  if (options.disparities.empty() && options.stack == 0 && !options.all_in_focus && !options.shear)
    throw Error("nothing to do: give --disparities or --stack, --all-in-focus, or --shear with --out-lf");
}

void RunRefocus(const RefocusCommandOptions& options) {
  ValidateOptions(options);
  stages::RefocusStageOptions stage;
  stage.refocus = ToRefocusOptions(options.resampling);
  stage.occlusion_aware = !options.no_occlusion;
  stage.shear = options.shear;
  stage.sheared_out = options.out_lf;
  stage.bit_depth = options.bit_depth;

  const Stopwatch stopwatch;
  nlohmann::json views;
  Bundle bundle = LoadSelectedViews(options.input, options.views, views);
  nlohmann::ordered_json summary = {{"command", "refocus"}, {"input", options.input}};
  summary["views"] = views;
  const LightField& light_field = bundle.light_field;
  summary["light_field"] = {{"shape", ToString(light_field.shape())},
                            {"transfer", ToString(light_field.transfer)},
                            {"weights", light_field.HasWeights()}};
  summary["load_seconds"] = stopwatch.Seconds();

  // The all-in-focus image needs a disparity map: check it before any long computation.
  std::optional<DisparityMap> disparity_map;
  if (options.all_in_focus) {
    if (!options.disparity_path.empty()) {
      disparity_map = ReadPfm(options.disparity_path);
      stage.all_in_focus_source = options.disparity_path;
    } else if (bundle.disparity) {
      disparity_map = bundle.disparity;
      stage.all_in_focus_source = "input";
    } else {
      throw Error("--all-in-focus: " + options.input + " holds no disparity map; give --disparity DISP.pfm");
    }
    stage.all_in_focus_disparity = &*disparity_map;
  }
  stage.disparities = options.disparities;
  if (options.stack > 0) {
    const auto [low, high] = StackRange(options, bundle);
    stage.disparities = edit::EvenlySpacedDisparities(low, high, options.stack);
  }
  stages::RunRefocusStage(bundle, stage, options.out, std::move(summary));
  spdlog::info("wrote {} ({:.2f} s)", options.out, stopwatch.Seconds());
}

void AddRefocusCommand(CLI::App& app) {
  auto options = std::make_shared<RefocusCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "refocus",
      "Shift-and-sum refocusing: a focal stack at chosen disparities, an all-in-focus image from a disparity map, "
      "and the sheared light field at a refocus level. Writes PNGs and summary.json into --out");
  command->add_option("light_field", options->input, "Input light field (views folder, .h5 bundle or ESLF .png)")
      ->required();
  command
      ->add_option("--disparities", options->disparities,
                   "Refocus at these disparities, pixels per view step, comma-separated, e.g. -1,0,1.5 (default: none)")
      ->delimiter(',')
      ->allow_extra_args(false);  // one value per occurrence: never swallow the positional light field
  command->add_option("--stack", options->stack,
                      "Refocus at N disparities evenly spaced over --range, else the input's recorded disparity "
                      "range, else its disparity map's range (default: 0, no stack)");
  command->add_option("--range", options->range, "MIN,MAX disparity range for --stack (default: from the input)")
      ->delimiter(',')
      ->expected(2);
  command->add_flag("--all-in-focus", options->all_in_focus,
                    "Write all_in_focus.png: every pixel focused at its own disparity (default: off)");
  command->add_option("--disparity", options->disparity_path,
                      "Centre-view disparity map (.pfm) for --all-in-focus (default: the input's own, e.g. "
                      "gt_disp_lowres.pfm beside HCI views or the bundle's disparity dataset)");
  command->add_flag("--no-occlusion", options->no_occlusion,
                    "All-in-focus: average every ray along the disparity line, even those hidden by nearer "
                    "surfaces (default: occluded rays are left out)");
  command->add_option("--shear", options->shear,
                      "Shear the light field by S pixels per view step (points at disparity S become aligned; "
                      "every disparity decreases by S) and write it to --out-lf (default: no shear)");
  command->add_option("--out-lf", options->out_lf,
                      "Where to write the sheared light field: .h5 bundle (with weights marking rays that came from "
                      "outside a view), .png ESLF or a views folder (default: none)");
  AddRefocusArguments(command, options->resampling);
  command->add_option("--bit-depth", options->bit_depth, "Bits per sample of the PNGs written: 8 or 16 (default: 8)");
  command->add_option("--out", options->out, "Output folder (replaced atomically when complete)")->required();
  AddViewsOption(command, options->views);
  command->callback([options] { RunRefocus(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(110, "refocus", AddRefocusCommand);

}  // namespace lfsp::cli
