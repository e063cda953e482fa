// `lfsp evaluate depth ALGO.pfm --gt GT.pfm [--json OUT]`: the HCI benchmark's general metrics, over all pixels and
// near ground-truth discontinuities, printed as JSON (and optionally written to a file).

#include <iostream>
#include <memory>
#include <string>

#include "arguments/evaluate_arguments.h"
#include "evaluate_registry.h"
#include "lfsp/core/pfm.h"
#include "lfsp/depth/metrics.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct EvaluateDepthOptions {
  std::string algo;
  std::string gt;
  std::string json;
  depth::MetricOptions metrics;
};

void RunEvaluateDepth(const EvaluateDepthOptions& options) {
  const DisparityMap algo = ReadPfm(options.algo);
  const DisparityMap gt = ReadPfm(options.gt);
  const depth::DepthEvaluation evaluation = depth::EvaluateDisparity(algo, gt, options.metrics);
  nlohmann::json report = depth::ToJson(evaluation);
  report["algo"] = options.algo;
  report["gt"] = options.gt;
  std::cout << report.dump(2) << "\n";
  if (!options.json.empty()) stages::WriteJsonSummary(report, options.json);
}

void AddEvaluateDepth(CLI::App& evaluate) {
  auto options = std::make_shared<EvaluateDepthOptions>();
  CLI::App* command = evaluate.add_subcommand(
      "depth",
      "HCI 4D light-field benchmark metrics of a centre-view disparity map: MSE x100, BadPix 0.07/0.03/0.01 (%), Q25 "
      "(1/100 px), with a 15 px frame ignored; also restricted to pixels near ground-truth depth discontinuities");
  command->add_option("algo", options->algo, "Disparity map to score (PFM, HCI convention)")->required();
  command->add_option("--gt", options->gt, "Ground-truth disparity (PFM, e.g. gt_disp_lowres.pfm)")->required();
  command->add_option("--json", options->json, "Also write the metrics to this JSON file (default: none)");
  AddDepthMetricArguments(command, options->metrics);
  command->callback([options] { RunEvaluateDepth(*options); });
}

}  // namespace

LFSP_REGISTER_EVALUATE_SUBCOMMAND(10, "depth", AddEvaluateDepth);

}  // namespace lfsp::cli
