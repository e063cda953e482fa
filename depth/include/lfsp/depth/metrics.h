#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp::depth {

// The HCI 4D light-field benchmark's general metrics (evaluation-toolkit, misc.get_general_metrics), computed the
// way the toolkit computes them on the low-resolution ground truth:
//   evaluation mask  = every pixel except a 15 px frame on each side (scene.get_boundary_mask),
//   MSE x100         = 100 * mean((gt - algo)^2) over mask & finite(algo) & finite(gt),
//   BadPix(t)        = 100 * #(|algo - gt| > t) / #mask; a NaN difference is never "bad" but still counts in #mask,
//                      exactly as numpy's comparison does in the toolkit,
//   Q25              = sorted(100 * |algo - gt|)[floor(N * 25 / 100)] over mask & finite(diff) & finite(algo).
struct DepthMetrics {
  double mse_x100 = 0.0;
  double badpix_007 = 0.0;  // percent
  double badpix_003 = 0.0;  // percent
  double badpix_001 = 0.0;  // percent
  double q25 = 0.0;         // 1/100 px
  std::size_t pixels = 0;   // #mask (the BadPix denominator)
};

struct MetricOptions {
  int boundary = 15;                  // ignored frame in pixels (toolkit boundary_offset at gt_scale 1)
  double discontinuity_jump = 0.1;    // a GT disparity step (px/view) between 4-neighbours that counts as an edge
  double discontinuity_radius = 5.0;  // pixels within this Euclidean distance of such an edge are "near"
};

// Metrics over all evaluated pixels and over the pixels near ground-truth depth discontinuities.
struct DepthEvaluation {
  DepthMetrics all;
  DepthMetrics near_discontinuities;
  MetricOptions options;
};

// Pixels whose ground-truth disparity differs by more than `jump` from a 4-neighbour (both sides of the step are
// marked), dilated to every pixel within `radius` (Euclidean). CV_8U, 255 = near a discontinuity. Non-finite GT
// values never create an edge. This is our own definition: the toolkit's mask_discontinuities.png is not
// distributed with the low-resolution data, so we derive the region from the ground truth itself.
cv::Mat DiscontinuityRegion(const DisparityMap& gt, double jump, double radius);

// The toolkit's evaluation frame: CV_8U, 255 inside, 0 on the `boundary`-wide frame.
cv::Mat BoundaryMask(int width, int height, int boundary);

// General metrics restricted to `region` (CV_8U, nonzero = evaluate), which is intersected with the boundary mask.
// Throws lfsp::Error if the sizes differ.
DepthMetrics ComputeMetrics(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary = 15);

// Both metric sets; throws lfsp::Error naming the sizes when algo and gt differ in size or are empty.
DepthEvaluation EvaluateDisparity(const DisparityMap& algo, const DisparityMap& gt, const MetricOptions& options = {});

nlohmann::json ToJson(const DepthMetrics& metrics);
nlohmann::json ToJson(const DepthEvaluation& evaluation);

}  // namespace lfsp::depth
