#include "stages/evaluate_stage.h"

#include <optional>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/segment/metrics.h"

namespace lfsp::stages {

nlohmann::json EvaluateSegmentationParts(const LightField* light_field, const Labels& labels,
                                         const DisparityMap* disparity, GroundTruth truth,
                                         segment::EvaluationOptions options, const std::string& source,
                                         bool use_recorded_parameters) {
  segment::EvaluationInputs inputs;
  inputs.light_field = light_field;
  inputs.labels = &labels;
  inputs.gt_labels = truth.labels;
  // Labels made on a decode's well-lit central views (segment's default) are scored against the same central views
  // of the ground truth, which covers every view of the decode.
  std::optional<Labels> central_truth;
  const LightFieldShape& shape = labels.shape();
  if (truth.labels != nullptr) {
    const LightFieldShape& whole = truth.labels->shape();
    const bool more_views = whole.nu != shape.nu || whole.nv != shape.nv;
    if (more_views && whole.width == shape.width && whole.height == shape.height) {
      if (shape.nu != shape.nv || whole.nu < shape.nu || whole.nv < shape.nv || (whole.nu - shape.nu) % 2 != 0 ||
          (whole.nv - shape.nv) % 2 != 0) {
        throw Error("the ground-truth labels have " + ToString(whole) + " and the segmentation " + ToString(shape) +
                    ": the segmentation's views are not the central views of the truth's");
      }
      central_truth = CentralViews(*truth.labels, shape.nu);
      inputs.gt_labels = &*central_truth;
    }
  }
  inputs.gt_disparity = truth.disparity;
  inputs.segmentation_disparity = disparity;
  options.refocus = options.refocus && disparity != nullptr;
  if (light_field != nullptr && use_recorded_parameters) {
    const Metadata& metadata = light_field->metadata;
    if (metadata.contains("lfsp_segment") && metadata["lfsp_segment"].contains("parameters"))
      options.lfsp = segment::ParamsFromJson(metadata["lfsp_segment"]["parameters"], source + " metadata");
  }
  options.baseline.size = options.lfsp.size;
  return segment::EvaluateSegmentation(inputs, options);
}

nlohmann::json EvaluateSegmentationBundle(const Bundle& segmentation, GroundTruth truth,
                                          segment::EvaluationOptions options, const std::string& source) {
  return EvaluateSegmentationParts(&segmentation.light_field, *segmentation.labels,
                                   segmentation.disparity ? &*segmentation.disparity : nullptr, truth,
                                   std::move(options), source);
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
