#include "lfsp/segment/evaluate.h"

#include <algorithm>
#include <optional>

#include "lfsp/core/error.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/segment/khan_metrics.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "lfsp/segment/refocus.h"

namespace lfsp::segment {
namespace {

// Runs one baseline, times it and scores it like the segmentation under test.
template <typename Run>
nlohmann::json ScoreBaseline(Run run, const EvaluationInputs& inputs, const std::vector<DisparityMap>* views,
                             int tolerance, bool per_view) {
  const Stopwatch stopwatch;
  const Labels labels = run();
  const double seconds = stopwatch.Seconds();
  nlohmann::json metrics = per_view
                               ? ScorePerViewLabels(labels, inputs.gt_labels, inputs.gt_disparity, views, tolerance)
                               : ScoreLabels(labels, inputs.gt_labels, inputs.gt_disparity, views, tolerance);
  metrics["seconds"] = seconds;
  return metrics;
}

nlohmann::json RefocusSweep(const EvaluationInputs& inputs, const EvaluationOptions& options, Progress& progress) {
  const DisparityMap& reference =
      inputs.gt_disparity != nullptr ? *inputs.gt_disparity : *inputs.segmentation_disparity;
  nlohmann::json sweep = nlohmann::json::array();
  for (double level : options.refocus_levels) {
    const LightField refocused = RefocusLightField(*inputs.light_field, level);
    const LfspResult result =
        SegmentLightField(refocused, RefocusDisparity(*inputs.segmentation_disparity, level), options.lfsp);
    const DisparityMap refocused_reference = RefocusDisparity(reference, level);
    const std::vector<DisparityMap> views = PropagateDisparity(refocused_reference, refocused.shape());
    const Labels carried = CarryCentreLabels(result.labels, refocused_reference, views);
    sweep.push_back({{"level", level},
                     {"ss", SelfSimilarity(result.labels, views)},
                     {"ss_in_frame", SelfSimilarity(result.labels, views, true)},
                     {"ss_reference", SelfSimilarity(carried, views)},
                     {"elr", EffectiveLabelRatio(result.labels)},
                     {"seconds", result.timings.total_seconds}});
    progress.Tick();
  }
  return sweep;
}

// Scoring sizes its tables by the largest label value; labels read from a file may be sparse (one label of
// 5,000,000 in a small bundle), so those are renumbered densely first. Dense labels are used in place.
const Labels* DenseLabels(const Labels* labels, std::optional<Labels>& storage) {
  if (labels == nullptr) return nullptr;
  std::int32_t largest = -1;
  for (std::size_t i = 0; i < labels->size(); ++i) largest = std::max(largest, labels->data()[i]);
  if (static_cast<std::uint64_t>(std::max(largest, 0)) < labels->size()) return labels;
  storage = DenselyRelabelled(*labels);
  return &*storage;
}

}  // namespace

nlohmann::json ScoreLabels(const Labels& labels, const Labels* gt_labels, const DisparityMap* gt_disparity,
                           const std::vector<DisparityMap>* gt_view_disparity, int boundary_tolerance) {
  const bool consistency = gt_disparity != nullptr && gt_view_disparity != nullptr;
  nlohmann::json m;
  // The label counts once: the effective label ratio is their quotient.
  const int label_count = LabelCount(labels), centre_label_count = CentreLabelCount(labels);
  m["labels"] = label_count;
  m["centre_labels"] = centre_label_count;
  m["elr"] = EffectiveLabelRatio(centre_label_count, label_count);
  m["compactness"] = Compactness(labels);
  // The overlap scores from one count of the overlaps, Khan's region error among them.
  std::optional<OverlapScores> overlaps;
  if (gt_labels != nullptr) overlaps = ScoreOverlaps(labels, *gt_labels);
  // Both self-similarity definitions and both framings from one pass over the rays (six passes before).
  std::optional<CarriedCentroids> centroids;
  if (consistency) centroids = CarriedCentroidSumsBoth(labels, *gt_view_disparity);
  m["khan"] = ScoreKhan(labels, gt_labels, consistency ? gt_view_disparity : nullptr,
                        overlaps ? std::optional<double>(overlaps->region_undersegmentation_error) : std::nullopt,
                        centroids ? std::optional<double>(KhanSelfSimilarityOfSums(
                                        centroids->all, centroids->label_count, labels.shape()))
                                  : std::nullopt);
  if (gt_labels != nullptr) {
    m["boundary_recall"] = BoundaryRecall(labels, *gt_labels, boundary_tolerance);
    m["undersegmentation_error"] = overlaps->undersegmentation_error;
    m["undersegmentation_error_region"] = overlaps->region_undersegmentation_error;
    m["achievable_segmentation_accuracy"] = overlaps->achievable_segmentation_accuracy;
  }
  if (consistency) {
    const LightFieldShape& shape = labels.shape();
    m["self_similarity"] = SelfSimilarityOfSums(centroids->all, centroids->label_count, shape);
    m["self_similarity_in_frame"] = SelfSimilarityOfSums(centroids->in_frame, centroids->label_count, shape);
    const Labels reference = CarryCentreLabels(labels, *gt_disparity, *gt_view_disparity);
    const CarriedCentroids carried = CarriedCentroidSumsBoth(reference, *gt_view_disparity);
    m["self_similarity_reference"] = SelfSimilarityOfSums(carried.all, carried.label_count, shape);
    m["self_similarity_reference_in_frame"] = SelfSimilarityOfSums(carried.in_frame, carried.label_count, shape);
    m["labels_per_pixel"] = LabelsPerPixel(labels, *gt_disparity, *gt_view_disparity);
    // What a perfectly consistent segmentation with the same centre superpixels scores under Khan's definitions.
    m["khan"]["self_similarity_reference"] = KhanSelfSimilarityOfSums(carried.all, carried.label_count, shape);
    m["khan"]["labels_per_pixel_reference"] = KhanLabelsPerPixel(reference, *gt_view_disparity);
  }
  return m;
}

nlohmann::json ScorePerViewLabels(const Labels& labels, const Labels* gt_labels, const DisparityMap* gt_disparity,
                                  const std::vector<DisparityMap>* gt_view_disparity, int boundary_tolerance) {
  nlohmann::json metrics = ScoreLabels(labels, gt_labels, nullptr, nullptr, boundary_tolerance);
  if (gt_disparity != nullptr && gt_view_disparity != nullptr) {
    const Labels followed = FollowToCentre(labels, *gt_view_disparity);
    const nlohmann::json consistency =
        ScoreLabels(followed, nullptr, gt_disparity, gt_view_disparity, boundary_tolerance);
    for (const char* key : {"self_similarity", "self_similarity_in_frame", "self_similarity_reference",
                            "self_similarity_reference_in_frame", "labels_per_pixel"}) {
      metrics[key] = consistency[key];
    }
    for (const char* key :
         {"self_similarity", "labels_per_pixel", "self_similarity_reference", "labels_per_pixel_reference"})
      metrics["khan"][key] = consistency["khan"][key];
  }
  metrics["note"] =
      "per-view method: self-similarity and labels per pixel after following each superpixel to the centre "
      "superpixel it overlaps most (through the ground-truth disparity); ELR counts its labels as they are, as the "
      "LFSP paper does for SLIC";
  return metrics;
}

nlohmann::json EvaluateSegmentation(const EvaluationInputs& given, const EvaluationOptions& options) {
  if (given.labels == nullptr) throw Error("evaluate segmentation: no labels to score");
  EvaluationInputs inputs = given;
  std::optional<Labels> dense_labels, dense_gt_labels;
  inputs.labels = DenseLabels(given.labels, dense_labels);
  inputs.gt_labels = DenseLabels(given.gt_labels, dense_gt_labels);
  const LightFieldShape& shape = inputs.labels->shape();
  std::optional<std::vector<DisparityMap>> views;
  if (inputs.gt_disparity != nullptr) views = PropagateDisparity(*inputs.gt_disparity, shape);
  const std::vector<DisparityMap>* view_pointer = views ? &*views : nullptr;

  // Drawn only on a terminal: the scoring, each baseline, each refocus level.
  Progress progress("evaluate",
                    1 + (options.baselines ? 4 : 0) + (options.refocus ? options.refocus_levels.size() : 0));
  nlohmann::json report;
  report["shape"] = ToString(shape);
  report["boundary_tolerance"] = options.boundary_tolerance;
  report["lfsp"] =
      ScoreLabels(*inputs.labels, inputs.gt_labels, inputs.gt_disparity, view_pointer, options.boundary_tolerance);
  progress.Tick();
  if (options.baselines) {
    if (inputs.light_field == nullptr) throw Error("evaluate segmentation: the baselines need the light field");
    const LightField& lf = *inputs.light_field;
    const BaselineParams& b = options.baseline;
    const int tol = options.boundary_tolerance;
    nlohmann::json baselines;
    baselines["slic_per_view"] = ScoreBaseline([&] { return SlicPerView(lf, b); }, inputs, view_pointer, tol, true);
    progress.Tick();
    baselines["lsc_per_view"] = ScoreBaseline([&] { return LscPerView(lf, b); }, inputs, view_pointer, tol, true);
    progress.Tick();
    baselines["slic_supervoxels_row_first"] =
        ScoreBaseline([&] { return SlicSupervoxels(lf, ViewOrder::kRowFirst, b); }, inputs, view_pointer, tol, false);
    progress.Tick();
    baselines["slic_supervoxels_column_first"] = ScoreBaseline(
        [&] { return SlicSupervoxels(lf, ViewOrder::kColumnFirst, b); }, inputs, view_pointer, tol, false);
    progress.Tick();
    report["baselines"] = baselines;
  }
  if (options.refocus) {
    if (inputs.light_field == nullptr || inputs.segmentation_disparity == nullptr) {
      throw Error("evaluate segmentation: the refocus sweep needs the light field and the disparity LFSP used");
    }
    report["refocus"] = RefocusSweep(inputs, options, progress);
  }
  return report;
}

}  // namespace lfsp::segment
