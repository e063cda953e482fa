#include "stages/recolor_stage.h"

#include <spdlog/spdlog.h>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/core/visualize.h"
#include "lfsp/edit/colour_adjust.h"
#include "stages/summary.h"

namespace lfsp::stages {
namespace fs = std::filesystem;

namespace {

// Preview names beside the output: out/edited.h5 -> out/edited.before.png and out/edited.after.png.
fs::path PreviewPath(const fs::path& out, const std::string& which) {
  fs::path name = out.stem();
  name += "." + which + ".png";
  return out.parent_path() / name;
}

}  // namespace

RecolorStageResult RunRecolorStage(Bundle& bundle, const RecolorStageOptions& options, const fs::path& out,
                                   nlohmann::ordered_json summary) {
  if (!bundle.labels) throw Error("recolour: the light field has no labels");
  const Stopwatch stopwatch;
  nlohmann::ordered_json timings;
  RecolorStageResult result;
  LightField& light_field = bundle.light_field;
  const ViewIndex centre = light_field.shape().Centre();
  result.before = DisplayEncoded(light_field.View(centre), light_field.transfer);
  Stopwatch step;
  result.stats = edit::Recolor(light_field, *bundle.labels, options.selection, options.recolor);
  timings["recolor_s"] = step.Lap();
  result.after = DisplayEncoded(light_field.View(centre), light_field.transfer);

  SaveLightField(bundle, out, options.bit_depth);
  const fs::path before_path = PreviewPath(out, "before");
  const fs::path after_path = PreviewPath(out, "after");
  WriteImage(result.before, before_path);
  WriteImage(result.after, after_path);
  timings["save_s"] = step.Lap();

  const edit::RecolorStats& stats = result.stats;
  const edit::ColourAdjustment& adjustment = options.recolor.adjustment;
  summary["selection"] = options.how;
  summary["selected_labels"] = options.selection;
  summary["adjustment"] = {{"space", edit::ToString(adjustment.space)},
                           {"hue_degrees", adjustment.hue_degrees},
                           {"saturation", adjustment.saturation},
                           {"value", adjustment.value},
                           {"feather_px", options.recolor.feather_px},
                           {"ray_weights", options.recolor.use_ray_weights && light_field.HasWeights()}};
  const double total_rays = static_cast<double>(light_field.shape().Views() * light_field.shape().ViewPixels());
  summary["rays"] = {{"total", static_cast<std::size_t>(total_rays)},
                     {"selected", stats.selected_rays},
                     {"feather", stats.feather_rays},
                     {"changed", stats.changed_rays},
                     {"selected_fraction", static_cast<double>(stats.selected_rays) / total_rays},
                     {"selected_per_view", stats.selected_rays_per_view}};
  // Outputs by name: they lie beside the summary, wherever the folder is moved (a pipeline run is built elsewhere).
  summary["outputs"] = {{"light_field", out.filename().string()},
                        {"before_preview", before_path.filename().string()},
                        {"after_preview", after_path.filename().string()}};
  timings["stage_s"] = stopwatch.Seconds();
  summary["timings"] = timings;
  WriteJsonSummary(summary, SummaryPathFor(out));
  spdlog::info("recoloured {} rays ({} in the feather band); wrote {}", stats.changed_rays, stats.feather_rays,
               out.string());
  result.summary = std::move(summary);
  return result;
}

}  // namespace lfsp::stages
