#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/segment/evaluate.h"

namespace lfsp::stages {

// What a run is scored against; either part may be missing.
struct GroundTruth {
  const DisparityMap* disparity = nullptr;  // centre-view disparity
  const Labels* labels = nullptr;           // object labels of every ray
};

// `lfsp evaluate segmentation`: every metric of a segmentation bundle (as the segment stage writes it: light field,
// the disparity LFSP ran with, labels, parameters in the metadata, which the refocus sweep re-runs with).
// `options.lfsp` is replaced by the recorded parameters when the bundle has them; `source` names the bundle.
nlohmann::json EvaluateSegmentationBundle(const Bundle& segmentation, GroundTruth truth,
                                          segment::EvaluationOptions options, const std::string& source);

// The same from the parts of a segmentation (the Python module's arrays): `labels` made by LFSP on `light_field`
// (null: no refocus sweep, no baselines) with `disparity` (null: no refocus sweep). The LFSP parameters the sweep
// re-runs with are the light field's metadata's when it records them (metadata["lfsp_segment"]) and
// `use_recorded_parameters`, else `options.lfsp`.
nlohmann::json EvaluateSegmentationParts(const LightField* light_field, const Labels& labels,
                                         const DisparityMap* disparity, GroundTruth truth,
                                         segment::EvaluationOptions options, const std::string& source,
                                         bool use_recorded_parameters = true);

// The scores of a pipeline run, with no re-runs: the disparity against the true one (HCI metrics), the labels
// against the true labels and disparity (ScoreLabels). Missing truth leaves its metrics out.
nlohmann::ordered_json ScoreRun(const DisparityMap& disparity, const Labels& labels, GroundTruth truth,
                                int boundary_tolerance = 2);

}  // namespace lfsp::stages
