#include "stages/refocus_stage.h"

#include <spdlog/spdlog.h>

#include <cstdio>
#include <string>
#include <vector>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/parallel_for.h"
#include "lfsp/core/shear.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/core/visualize.h"
#include "lfsp/edit/image_measures.h"
#include "stages/summary.h"

namespace lfsp::stages {
namespace fs = std::filesystem;

std::string FocalStackSliceName(std::size_t index, float disparity) {
  char name[64];
  std::snprintf(name, sizeof(name), "refocus_%02zu_d%+.3f.png", index, static_cast<double>(disparity));
  return name;
}

ShearInterpolation InterpolationFromName(const std::string& name) {
  if (name == "linear") return ShearInterpolation::kLinear;
  if (name == "cubic") return ShearInterpolation::kCubic;
  throw Error("interpolation: expected linear or cubic, got '" + name + "'");
}

std::string InterpolationName(ShearInterpolation interpolation) {
  return interpolation == ShearInterpolation::kCubic ? "cubic" : "linear";
}

RefocusStageResult RunRefocusStage(const Bundle& bundle, const RefocusStageOptions& options, const fs::path& out,
                                   nlohmann::ordered_json summary) {
  const Stopwatch stopwatch;
  const LightField& light_field = bundle.light_field;
  RefocusStageResult result;
  nlohmann::ordered_json timings;
  AtomicOutput output(out);
  fs::create_directories(output.temporary());

  if (!options.disparities.empty()) {
    Stopwatch step;
    // Each slice is refocused on every core in turn; then the slices are encoded, written and measured a slice per
    // core: a PNG's deflate runs on one core, and written one after the other the slices' deflate was a quarter of
    // the stage's CPU samples (perf, full-size Illum).
    for (const float disparity : options.disparities)
      result.slices.push_back(edit::RefocusImage(light_field, disparity, options.refocus));
    const std::size_t count = result.slices.size();
    std::vector<std::string> names(count);
    std::vector<double> sharpness(count);
    ParallelFor(static_cast<int>(count), [&](int slice) {
      const auto i = static_cast<std::size_t>(slice);
      names[i] = FocalStackSliceName(i, options.disparities[i]);
      WriteImage(DisplayEncoded(result.slices[i], light_field.transfer), output.temporary() / names[i],
                 options.bit_depth);
      sharpness[i] = edit::GradientEnergy(result.slices[i]);
    });
    nlohmann::ordered_json slices = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < count; ++i) {
      slices.push_back({{"disparity", options.disparities[i]}, {"file", names[i]}, {"sharpness", sharpness[i]}});
      spdlog::info("refocused at disparity {:+.3f} -> {}", options.disparities[i], names[i]);
    }
    summary["focal_stack"] = slices;
    timings["focal_stack_s"] = step.Seconds();
  }

  if (options.all_in_focus_disparity != nullptr) {
    Stopwatch step;
    edit::AllInFocusOptions all_options;
    all_options.use_ray_weights = options.refocus.use_ray_weights;
    all_options.occlusion_aware = options.occlusion_aware;
    const cv::Mat image = edit::AllInFocus(light_field, *options.all_in_focus_disparity, all_options);
    WriteImage(DisplayEncoded(image, light_field.transfer), output.temporary() / "all_in_focus.png", options.bit_depth);
    const cv::Mat centre = light_field.View(light_field.shape().Centre());
    summary["all_in_focus"] = {{"file", "all_in_focus.png"},
                               {"disparity", options.all_in_focus_source},
                               {"occlusion_aware", all_options.occlusion_aware},
                               {"sharpness", edit::GradientEnergy(image)},
                               {"psnr_vs_centre_view_db", edit::Psnr(centre, image)}};
    timings["all_in_focus_s"] = step.Seconds();
  }

  if (options.shear) {
    Stopwatch step;
    ShearOptions shear_options;
    shear_options.interpolation = options.refocus.interpolation;
    Bundle sheared;
    sheared.light_field = ShearLightField(light_field, *options.shear, shear_options);
    if (bundle.disparity) sheared.disparity = ShearDisparity(*bundle.disparity, *options.shear);
    if (bundle.labels) sheared.labels = ShearLabels(*bundle.labels, *options.shear);
    SaveLightField(sheared, options.sheared_out, options.bit_depth);
    summary["shear"] = {{"disparity", *options.shear}, {"out", options.sheared_out.string()}};
    timings["shear_s"] = step.Seconds();
  }

  summary["parameters"] = {{"interpolation", InterpolationName(options.refocus.interpolation)},
                           {"ray_weights", options.refocus.use_ray_weights},
                           {"bit_depth", options.bit_depth}};
  timings["stage_s"] = stopwatch.Seconds();
  summary["timings"] = timings;
  WriteJsonSummary(summary, output.temporary() / "summary.json");
  output.Commit();
  result.summary = std::move(summary);
  return result;
}

}  // namespace lfsp::stages
