// `lfsp evaluate depth ALGO.pfm --gt GT.pfm [--json OUT]`: the HCI benchmark's general metrics, over all pixels and
// near ground-truth discontinuities, printed as JSON (and optionally written to a file).

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "arguments/evaluate_arguments.h"
#include "evaluate_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/core/pfm.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/depth/region_metrics.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct EvaluateDepthOptions {
  std::string algo;
  std::string gt;
  std::string json;
  std::string confidence;
  std::string masks;
  depth::MetricOptions metrics;
};

// `lfsp depth --out D.pfm` writes its confidence as D_confidence.pfm: found there when not named.
std::filesystem::path ConfidencePath(const EvaluateDepthOptions& options) {
  if (!options.confidence.empty()) return options.confidence;
  const std::filesystem::path algo(options.algo);
  const std::filesystem::path beside = algo.parent_path() / (algo.stem().string() + "_confidence.pfm");
  return std::filesystem::exists(beside) ? beside : std::filesystem::path();
}

void RunEvaluateDepth(const EvaluateDepthOptions& options) {
  const DisparityMap algo = ReadPfm(options.algo);
  const DisparityMap gt = ReadPfm(options.gt);
  const std::filesystem::path masks_folder =
      options.masks.empty() ? std::filesystem::path(options.gt).parent_path() : std::filesystem::path(options.masks);
  if (!options.masks.empty() && !std::filesystem::is_directory(masks_folder))
    throw Error(options.masks + ": --masks is not a folder");
  const depth::EvaluationMasks masks = depth::ReadEvaluationMasks(masks_folder, gt, options.metrics);
  const std::filesystem::path confidence_path = ConfidencePath(options);
  std::optional<DisparityMap> confidence;
  if (!confidence_path.empty()) confidence = ReadPfm(confidence_path);
  const depth::DepthEvaluation evaluation =
      depth::EvaluateDisparity(algo, gt, options.metrics, masks, confidence ? &*confidence : nullptr);
  nlohmann::json report = depth::ToJson(evaluation);
  report["algo"] = options.algo;
  report["gt"] = options.gt;
  if (confidence) report["confidence"] = confidence_path.string();
  std::cout << report.dump(2) << "\n";
  if (!options.json.empty()) stages::WriteJsonSummary(report, options.json);
}

void AddEvaluateDepth(CLI::App& evaluate) {
  auto options = std::make_shared<EvaluateDepthOptions>();
  CLI::App* command = evaluate.add_subcommand(
      "depth",
      "HCI 4D light-field benchmark metrics of a centre-view disparity map: MSE x100, BadPix 0.07/0.03/0.01 (%), Q25 "
      "(1/100 px), with a 15 px frame ignored; the same near ground-truth depth discontinuities; the fattening index "
      "(% of bad pixels that read nearer); bumpiness on planes and smooth surfaces; and, with a confidence map, the "
      "area under its sparsification curve against the oracle's");
  command->add_option("algo", options->algo, "Disparity map to score (PFM, HCI convention)")->required();
  command->add_option("--gt", options->gt, "Ground-truth disparity (PFM, e.g. gt_disp_lowres.pfm)")->required();
  command->add_option("--json", options->json, "Also write the metrics to this JSON file (default: none)");
  command->add_option("--confidence", options->confidence,
                      "Confidence map (PFM, larger = more trusted) to score by its sparsification curve (default: "
                      "ALGO's <name>_confidence.pfm when it exists, as `lfsp depth` writes it; else none)");
  command->add_option("--masks", options->masks,
                      "Folder with the benchmark's mask_discontinuities.png, mask_planes.png, mask_smooth_surfaces.png "
                      "(ground-truth size or an integer multiple); a missing one is derived from the ground truth "
                      "(default: the ground truth's folder)");
  AddDepthMetricArguments(command, options->metrics);
  command->callback([options] { RunEvaluateDepth(*options); });
}

}  // namespace

LFSP_REGISTER_EVALUATE_SUBCOMMAND(10, "depth", AddEvaluateDepth);

}  // namespace lfsp::cli
