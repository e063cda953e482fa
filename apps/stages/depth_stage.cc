#include "stages/depth_stage.h"

#include <spdlog/spdlog.h>

#include "lfsp/core/stopwatch.h"
#include "lfsp/depth/depth_io.h"
#include "lfsp/depth/lattice_peak.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/depth/region_metrics.h"
#include "stages/summary.h"

namespace lfsp::stages {

DepthStageResult RunDepthStage(const Bundle& bundle, const depth::DepthOptions& options,
                               const std::filesystem::path& disparity_pfm, nlohmann::ordered_json summary) {
  const Stopwatch stopwatch;
  DepthStageResult result;
  const depth::DepthResult& estimate = result.estimate = depth::EstimateDepth(bundle.light_field, options);
  const double estimate_seconds = stopwatch.Seconds();
  const depth::DepthOutputPaths paths = depth::OutputPathsFor(disparity_pfm);
  depth::WriteDepthOutputs(estimate, paths);
  const double write_seconds = stopwatch.Seconds() - estimate_seconds;

  // Outputs by name: they lie beside the summary, wherever the folder is moved (a pipeline run is built elsewhere).
  summary["outputs"] = {{"disparity", paths.disparity.filename().string()},
                        {"preview", paths.preview.filename().string()},
                        {"confidence", paths.confidence.filename().string()}};
  summary["range"] = {{"min", estimate.range.min}, {"max", estimate.range.max}, {"source", estimate.range_source}};
  summary["parameters"] = depth::ToJson(options);
  summary["occlusion_candidates"] = estimate.occlusion_candidates;
  summary["thin_structure_refusals"] = estimate.thin_structure_refusals;
  summary["mixed_edge_moves"] = estimate.mixed_edge_moves;
  const nlohmann::ordered_json choices = depth::AutomaticChoicesToJson(estimate);
  for (const auto& [key, value] : choices.items()) summary[key] = value;
  // How strongly the lens lattice shows in the maps of a lenslet decode (issue 49; about 1 is none), when they are
  // large enough to tell.
  if (const auto frequencies = depth::LensLatticeFrequencies(bundle.light_field)) {
    const auto confidence = depth::StrongestLatticePeak(estimate.confidence.Mat(), *frequencies);
    const auto disparity = depth::StrongestLatticePeak(estimate.disparity.Mat(), *frequencies);
    if (confidence && disparity)
      summary["lattice_peak"] = {{"confidence", depth::ToJson(*confidence)}, {"disparity", depth::ToJson(*disparity)}};
  }
  const std::optional<DisparityMap>& truth = bundle.disparity;
  if (truth && truth->width() == estimate.disparity.width() && truth->height() == estimate.disparity.height()) {
    const depth::MetricOptions metric_options;
    const depth::DepthEvaluation evaluation =
        depth::EvaluateDisparity(estimate.disparity, *truth, metric_options,
                                 depth::DeriveEvaluationMasks(*truth, metric_options), &estimate.confidence);
    summary["metrics_vs_input_ground_truth"] = depth::ToJson(evaluation);
    spdlog::info("vs ground truth: MSE x100 {:.2f}, BadPix 0.07 {:.2f} %", evaluation.all.mse_x100,
                 evaluation.all.badpix_007);
  }
  summary["timings_seconds"] = estimate.timings;
  summary["timings_seconds"]["estimate"] = estimate_seconds;
  summary["timings_seconds"]["write"] = write_seconds;
  summary["timings_seconds"]["stage"] = stopwatch.Seconds();
  WriteJsonSummary(summary, SummaryPathFor(paths.disparity));
  result.summary = std::move(summary);
  return result;
}

}  // namespace lfsp::stages
