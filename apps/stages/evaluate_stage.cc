#include "stages/evaluate_stage.h"

#include <vector>

#include "lfsp/depth/metrics.h"
#include "lfsp/segment/metrics.h"

namespace lfsp::stages {

nlohmann::json EvaluateSegmentationBundle(const Bundle& segmentation, GroundTruth truth,
                                          segment::EvaluationOptions options, const std::string& source) {
  segment::EvaluationInputs inputs;
  inputs.light_field = &segmentation.light_field;
  inputs.labels = &*segmentation.labels;
  inputs.gt_labels = truth.labels;
  inputs.gt_disparity = truth.disparity;
  inputs.segmentation_disparity = segmentation.disparity ? &*segmentation.disparity : nullptr;
  options.refocus = options.refocus && segmentation.disparity.has_value();
  const Metadata& metadata = segmentation.light_field.metadata;
  if (metadata.contains("lfsp_segment") && metadata["lfsp_segment"].contains("parameters"))
    options.lfsp = segment::ParamsFromJson(metadata["lfsp_segment"]["parameters"], source + " metadata");
  options.baseline.size = options.lfsp.size;
  return segment::EvaluateSegmentation(inputs, options);
}

nlohmann::ordered_json ScoreRun(const DisparityMap& disparity, const Labels& labels, GroundTruth truth,
                                int boundary_tolerance) {
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  std::vector<DisparityMap> view_disparity;
  if (truth.disparity != nullptr) {
    metrics["depth"] = depth::ToJson(depth::EvaluateDisparity(disparity, *truth.disparity));
    view_disparity = segment::PropagateDisparity(*truth.disparity, labels.shape());
  }
  metrics["segmentation"] =
      segment::ScoreLabels(labels, truth.labels, truth.disparity,
                           truth.disparity != nullptr ? &view_disparity : nullptr, boundary_tolerance);
  return metrics;
}

}  // namespace lfsp::stages
