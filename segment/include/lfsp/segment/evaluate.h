#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/baselines.h"
#include "lfsp/segment/params.h"
#include "lfsp/segment/refocus.h"

namespace lfsp::segment {

// What to score a light-field segmentation against. Every pointer may be null; metrics that need a missing input
// are left out of the report.
struct EvaluationInputs {
  const LightField* light_field = nullptr;               // needed for the baselines and the refocus sweep
  const Labels* labels = nullptr;                        // the segmentation to score (required)
  const Labels* gt_labels = nullptr;                     // ground-truth object labels of every ray: BR, UE, ASA
  const DisparityMap* gt_disparity = nullptr;            // ground-truth centre disparity: SS, labels per pixel
  const DisparityMap* segmentation_disparity = nullptr;  // the disparity LFSP ran with (refocus sweep)
};

struct EvaluationOptions {
  int boundary_tolerance = 2;  // pixels, chessboard distance
  bool baselines = false;      // also run and score per-view SLIC and LSC and SLIC supervoxels (row/column first)
  BaselineParams baseline;
  bool refocus = false;  // re-run LFSP on refocused light fields and report SS at each level
  std::vector<double> refocus_levels = DefaultRefocusLevels();
  LfspParams lfsp;  // parameters for the refocus re-runs
};

// All metrics of one labelling: labels/superpixel counts, ELR, compactness, and when the inputs allow it BR, UE
// (Neubert-Protzel and per-region), ASA, self-similarity (all rays, Eq. 8-10; only rays landing inside the centre
// view's frame; and both for the reference of CarryCentreLabels, what occlusions and borders cost on their own) and
// labels per pixel; and under "khan" the same family as Khan et al.'s evaluation defines it (khan_metrics.h), with
// the self-similarity and labels per pixel of the CarryCentreLabels reference.
// `gt_view_disparity` is the ground-truth disparity of every ray (PropagateDisparity of the centre map).
nlohmann::json ScoreLabels(const Labels& labels, const Labels* gt_labels, const DisparityMap* gt_disparity,
                           const std::vector<DisparityMap>* gt_view_disparity, int boundary_tolerance);

// The same for a method that segments each view on its own (label ids not shared between views): BR, UE, ASA, ELR
// and compactness on the labels as they are; self-similarity and labels per pixel after FollowToCentre, so that they
// measure where the superpixels lie rather than how the method happened to number them.
nlohmann::json ScorePerViewLabels(const Labels& labels, const Labels* gt_labels, const DisparityMap* gt_disparity,
                                  const std::vector<DisparityMap>* gt_view_disparity, int boundary_tolerance);

// The report of `lfsp evaluate segmentation`: {"lfsp": metrics, "baselines": {name: metrics}, "refocus": [...]}.
nlohmann::json EvaluateSegmentation(const EvaluationInputs& inputs, const EvaluationOptions& options);

}  // namespace lfsp::segment
