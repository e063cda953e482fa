// `lfsp evaluate segmentation OUT.h5 [--gt-disparity GT.pfm] [--gt-labels GT.h5] [--baselines]`: the superpixel
// metrics of a light-field segmentation (a bundle written by `lfsp segment`), printed as JSON: boundary recall, UE
// (Neubert-Protzel and per-region), ASA, compactness, self-similarity, effective label ratio, labels per pixel, the
// refocus sweep, and optionally the same metrics for per-view SLIC / LSC and SLIC supervoxels run on the same light
// field.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "arguments/evaluate_arguments.h"
#include "evaluate_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/pfm.h"
#include "lfsp/segment/evaluate.h"
#include "stages/evaluate_stage.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct EvaluateSegmentationOptions {
  std::string input;
  std::string gt_disparity;
  std::string gt_labels;
  std::string json;
  SegmentationEvaluationArguments scoring;
};

void RunEvaluateSegmentation(const EvaluateSegmentationOptions& options) {
  const segment::EvaluationOptions evaluation = ToEvaluationOptions(options.scoring);  // checks the levels first
  const Bundle bundle = ReadBundle(options.input);
  if (!bundle.labels) throw Error(options.input + ": no 'labels' dataset (write it with lfsp segment)");
  std::optional<DisparityMap> gt_disparity;
  if (!options.gt_disparity.empty()) gt_disparity = ReadPfm(options.gt_disparity);
  std::string gt_disparity_source = options.gt_disparity;
  std::optional<Labels> gt_labels;
  if (!options.gt_labels.empty()) {
    Bundle gt = ReadBundle(options.gt_labels);
    if (!gt.labels) throw Error(options.gt_labels + ": no 'labels' dataset (ground-truth labels of every ray)");
    gt_labels = std::move(gt.labels);
    if (!gt_disparity && gt.disparity) {  // a simulated bundle carries its ground-truth disparity too
      gt_disparity = std::move(gt.disparity);
      gt_disparity_source = options.gt_labels + " (its disparity)";
    }
  }

  const stages::GroundTruth truth{gt_disparity ? &*gt_disparity : nullptr, gt_labels ? &*gt_labels : nullptr};
  nlohmann::json report = stages::EvaluateSegmentationBundle(bundle, truth, evaluation, options.input);
  report["input"] = options.input;
  report["self_similarity_disparity"] = gt_disparity ? gt_disparity_source : std::string("none (give --gt-disparity)");
  if (gt_labels) report["gt_labels"] = options.gt_labels;
  if (!gt_disparity) spdlog::warn("no --gt-disparity: self-similarity and labels per pixel are not reported");
  std::cout << report.dump(2) << "\n";
  if (!options.json.empty()) stages::WriteJsonSummary(report, options.json);
}

void AddEvaluateSegmentation(CLI::App& evaluate) {
  auto options = std::make_shared<EvaluateSegmentationOptions>();
  CLI::App* command = evaluate.add_subcommand(
      "segmentation",
      "Superpixel metrics of a light-field segmentation (bundle with `labels`, from lfsp segment), as JSON: boundary "
      "recall, under-segmentation error (Neubert-Protzel and per-region), ASA, compactness, LFSP self-similarity, "
      "effective label ratio, labels per pixel, the refocus sweep; optionally the baselines side by side");
  command->add_option("input", options->input, "Segmentation bundle (.h5) with datasets LF, labels and disparity")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--gt-disparity", options->gt_disparity,
                   "Ground-truth centre-view disparity (PFM) for self-similarity, labels per pixel and the refocus "
                   "sweep (default: the --gt-labels bundle's disparity if it has one, else none)")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--gt-labels", options->gt_labels,
                   "Bundle (.h5) whose `labels` are ground-truth object labels of every ray, for BR/UE/ASA (old "
                   "HCI lf.h5 with labels.h5 beside it works too; default: none)")
      ->check(CLI::ExistingFile);
  AddSegmentationEvaluationArguments(command, options->scoring);
  command->add_option("--json", options->json, "Also write the report to this JSON file (default: none)");
  command->callback([options] { RunEvaluateSegmentation(*options); });
}

}  // namespace

LFSP_REGISTER_EVALUATE_SUBCOMMAND(20, "segmentation", AddEvaluateSegmentation);

}  // namespace lfsp::cli
