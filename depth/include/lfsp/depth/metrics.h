#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

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

// The sparsification curve of a confidence map (Ilg et al., ECCV 2018): the MSE x100 of the most confident p % of
// the evaluated pixels, for p = 1 ... 100, beside the same curve for the oracle order (smallest error first). The
// areas are the curves' means; the area between them (AUSE) is 0 for a confidence that ranks errors perfectly.
struct Sparsification {
  std::vector<double> curve;   // 100 values, p = 1 ... 100 %
  std::vector<double> oracle;  // 100 values
  double area = 0.0;
  double oracle_area = 0.0;
  double area_between = 0.0;  // area - oracle_area (AUSE)
};

// Metrics over all evaluated pixels and over the benchmark's regions (lfsp/depth/region_metrics.h): near
// ground-truth depth discontinuities, on planes and on smooth surfaces.
struct DepthEvaluation {
  DepthMetrics all;
  DepthMetrics near_discontinuities;  // on the discontinuity mask
  // Of the pixels bad at 0.07, the percentage that read nearer than the truth (FatteningIndex).
  double fattening_all = 0.0;
  double fattening_near_discontinuities = 0.0;
  // The benchmark's bumpiness (Bumpiness), 100 x mean clipped Hessian norm of the error.
  double bumpiness_planes = 0.0;
  double bumpiness_smooth_surfaces = 0.0;
  std::size_t plane_pixels = 0;
  std::size_t smooth_surface_pixels = 0;
  std::string discontinuities_source, planes_source, smooth_surfaces_source;
  std::optional<Sparsification> sparsification;  // when a confidence map was given
  MetricOptions options;
};

// Pixels whose ground-truth disparity differs by more than `jump` from a 4-neighbour (both sides of the step are
// marked), dilated to every pixel within `radius` (Euclidean). CV_8U, 255 = near a discontinuity. Non-finite GT
// values never create an edge. This is our own definition: the toolkit's mask_discontinuities.png is not
// distributed with the low-resolution data, so we derive the region from the ground truth itself.
cv::Mat DiscontinuityRegion(const DisparityMap& gt, double jump, double radius);

// Per pixel (CV_32F), the Euclidean distance to the nearest pixel of a jump of more than `jump` between finite
// 4-neighbours of `map` (both sides of a jump are at 0). The discontinuity region and the confidence's edge term
// (refinement.h) are both measured with it.
cv::Mat DistanceToDisparityJumps(const DisparityMap& map, double jump);

// The toolkit's evaluation frame: CV_8U, 255 inside, 0 on the `boundary`-wide frame.
cv::Mat BoundaryMask(int width, int height, int boundary);

// General metrics restricted to `region` (CV_8U, nonzero = evaluate), which is intersected with the boundary mask.
// Throws lfsp::Error if the sizes differ.
DepthMetrics ComputeMetrics(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary = 15);

// Every figure, with the regions derived from the ground truth (DeriveEvaluationMasks); throws lfsp::Error naming
// the sizes when algo and gt differ in size or are empty. region_metrics.h has the version with a scene's masks and a
// confidence map.
DepthEvaluation EvaluateDisparity(const DisparityMap& algo, const DisparityMap& gt, const MetricOptions& options = {});

nlohmann::json ToJson(const DepthMetrics& metrics);
nlohmann::json ToJson(const DepthEvaluation& evaluation);

}  // namespace lfsp::depth
