// `lfsp refocus LF --out DIR`: shift-and-sum refocused images (a focal stack), an all-in-focus image from a
// disparity map, and the sheared light field at a refocus level.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/refocus.h"
#include "lfsp/core/visualize.h"
#include "lfsp/edit/image_measures.h"
#include "lfsp/edit/refocus.h"
#include "summary.h"
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
  std::string interpolation = "linear";
  bool no_weights = false;
  int bit_depth = 8;
  std::string out;
};

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

ShearInterpolation InterpolationFromString(const std::string& name) {
  if (name == "linear") return ShearInterpolation::kLinear;
  if (name == "cubic") return ShearInterpolation::kCubic;
  throw Error("--interpolation: expected linear or cubic, got '" + name + "'");
}

// The range a --stack spans: --range, else the light field's recorded disparity range (HCI parameters.cfg), else
// the finite range of its disparity map.
std::pair<float, float> StackRange(const RefocusCommandOptions& options, const Bundle& bundle) {
  if (!options.range.empty()) {
    if (options.range.size() != 2) throw Error("--range: expected MIN,MAX");
    return {options.range[0], options.range[1]};
  }
  if (const auto range = DisparityRangeFromMetadata(bundle.light_field.metadata)) return {range->min, range->max};
  if (bundle.disparity) {
    float low = std::numeric_limits<float>::infinity();
    float high = -std::numeric_limits<float>::infinity();
    const std::size_t count =
        static_cast<std::size_t>(bundle.disparity->width()) * static_cast<std::size_t>(bundle.disparity->height());
    for (std::size_t i = 0; i < count; ++i) {
      const float d = bundle.disparity->data()[i];
      if (!std::isfinite(d)) continue;
      low = std::min(low, d);
      high = std::max(high, d);
    }
    if (low <= high) return {low, high};
  }
  throw Error("--stack: " + options.input +
              " records no disparity range and has no disparity map; give --range MIN,MAX or --disparities");
}

std::string SliceName(std::size_t index, float disparity) {
  char name[64];
  std::snprintf(name, sizeof(name), "refocus_%02zu_d%+.3f.png", index, static_cast<double>(disparity));
  return name;
}

// Disparities beyond this many pixels per view step move every ray out of any view: a typo, not a request.
constexpr float kMaxDisparity = 1000.0f;
constexpr int kMaxStack = 1000;

void RequireDisparity(float disparity, const char* option) {
  if (!std::isfinite(disparity) || std::abs(disparity) > kMaxDisparity)
    throw Error(std::string(option) + ": " + std::to_string(disparity) + " is not a disparity in -" +
                std::to_string(static_cast<int>(kMaxDisparity)) + ".." +
                std::to_string(static_cast<int>(kMaxDisparity)) + " px per view step");
}

void RunRefocus(const RefocusCommandOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.stack < 0 || options.stack > kMaxStack)
    throw Error("--stack: expected a number of slices in 1.." + std::to_string(kMaxStack));
  for (const float d : options.disparities) RequireDisparity(d, "--disparities");
  for (const float d : options.range) RequireDisparity(d, "--range");
  if (options.shear) RequireDisparity(*options.shear, "--shear");
  if (!options.disparities.empty() && options.stack > 0) throw Error("give either --disparities or --stack, not both");
  if (options.shear.has_value() != !options.out_lf.empty())
    throw Error("--shear S and --out-lf OUT go together: give both or neither");
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth: expected 8 or 16");
  const bool any_slices = !options.disparities.empty() || options.stack > 0;
  if (!any_slices && !options.all_in_focus && !options.shear)
    throw Error("nothing to do: give --disparities or --stack, --all-in-focus, or --shear with --out-lf");

  nlohmann::ordered_json summary;
  nlohmann::ordered_json timings;
  summary["command"] = "refocus";
  summary["input"] = options.input;

  auto step = std::chrono::steady_clock::now();
  Bundle bundle = LoadInput(options.input);
  summary["views"] = SelectViews(bundle, options.views, options.input);
  const LightField& light_field = bundle.light_field;
  timings["load_s"] = SecondsSince(step);
  summary["light_field"] = {{"shape", ToString(light_field.shape())},
                            {"transfer", ToString(light_field.transfer)},
                            {"weights", light_field.HasWeights()}};
  edit::RefocusOptions refocus_options;
  refocus_options.interpolation = InterpolationFromString(options.interpolation);
  refocus_options.use_ray_weights = !options.no_weights;

  // The all-in-focus image needs a disparity map: check it before any long computation.
  std::optional<DisparityMap> disparity_map;
  std::string disparity_source;
  if (options.all_in_focus) {
    if (!options.disparity_path.empty()) {
      disparity_map = ReadPfm(options.disparity_path);
      disparity_source = options.disparity_path;
    } else if (bundle.disparity) {
      disparity_map = bundle.disparity;
      disparity_source = "input";
    } else {
      throw Error("--all-in-focus: " + options.input + " holds no disparity map; give --disparity DISP.pfm");
    }
  }

  AtomicOutput output(options.out);
  fs::create_directories(output.temporary());

  if (any_slices) {
    step = std::chrono::steady_clock::now();
    std::vector<float> disparities = options.disparities;
    if (options.stack > 0) {
      const auto [low, high] = StackRange(options, bundle);
      disparities = edit::EvenlySpacedDisparities(low, high, options.stack);
    }
    nlohmann::ordered_json slices = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < disparities.size(); ++i) {
      const cv::Mat image = edit::RefocusImage(light_field, disparities[i], refocus_options);
      const std::string name = SliceName(i, disparities[i]);
      WriteImage(DisplayEncoded(image, light_field.transfer), output.temporary() / name, options.bit_depth);
      slices.push_back({{"disparity", disparities[i]}, {"file", name}, {"sharpness", edit::GradientEnergy(image)}});
      spdlog::info("refocused at disparity {:+.3f} -> {}", disparities[i], name);
    }
    summary["focal_stack"] = slices;
    timings["focal_stack_s"] = SecondsSince(step);
  }

  if (options.all_in_focus) {
    step = std::chrono::steady_clock::now();
    edit::AllInFocusOptions all_options;
    all_options.use_ray_weights = !options.no_weights;
    all_options.occlusion_aware = !options.no_occlusion;
    const cv::Mat image = edit::AllInFocus(light_field, *disparity_map, all_options);
    WriteImage(DisplayEncoded(image, light_field.transfer), output.temporary() / "all_in_focus.png", options.bit_depth);
    const cv::Mat centre = light_field.View(light_field.shape().Centre());
    summary["all_in_focus"] = {{"file", "all_in_focus.png"},
                               {"disparity", disparity_source},
                               {"occlusion_aware", all_options.occlusion_aware},
                               {"sharpness", edit::GradientEnergy(image)},
                               {"psnr_vs_centre_view_db", edit::Psnr(centre, image)}};
    timings["all_in_focus_s"] = SecondsSince(step);
  }

  if (options.shear) {
    step = std::chrono::steady_clock::now();
    ShearOptions shear_options;
    shear_options.interpolation = refocus_options.interpolation;
    Bundle sheared;
    sheared.light_field = ShearLightField(light_field, *options.shear, shear_options);
    if (bundle.disparity) sheared.disparity = ShearDisparity(*bundle.disparity, *options.shear);
    if (bundle.labels) sheared.labels = ShearLabels(*bundle.labels, *options.shear);
    SaveLightField(sheared, options.out_lf, options.bit_depth);
    summary["shear"] = {{"disparity", *options.shear}, {"out", options.out_lf}};
    timings["shear_s"] = SecondsSince(step);
  }

  summary["parameters"] = {
      {"interpolation", options.interpolation}, {"ray_weights", !options.no_weights}, {"bit_depth", options.bit_depth}};
  timings["total_s"] = SecondsSince(start);
  summary["timings"] = timings;
  WriteJsonSummary(summary, output.temporary() / "summary.json");
  output.Commit();
  spdlog::info("wrote {}", options.out);
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
  command->add_option("--interpolation", options->interpolation,
                      "Sub-pixel interpolation for refocusing and shearing: linear or cubic (default: linear)");
  command->add_flag("--no-weights", options->no_weights,
                    "Ignore the input's per-ray weights (default: rays are weighted by them when present)");
  command->add_option("--bit-depth", options->bit_depth, "Bits per sample of the PNGs written: 8 or 16 (default: 8)");
  command->add_option("--out", options->out, "Output folder (replaced atomically when complete)")->required();
  AddViewsOption(command, options->views);
  command->callback([options] { RunRefocus(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(110, "refocus", AddRefocusCommand);

}  // namespace lfsp::cli
