#pragma once

#include <array>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/segment/params.h"
#include "lfsp/segment/plane.h"

namespace lfsp::segment {

// Fits one plane per label of a centre-view label map (CV_32SC1, 0 .. count-1) to the centre-view disparity, by
// least squares re-fitted on the inliers (|d - plane| < inlier_threshold), starting from the median disparity.
// Labels with fewer than 3 usable samples, or degenerate (collinear) support, get a fronto-parallel plane.
std::vector<Plane> FitPlanes(const cv::Mat& labels, int count, const cv::Mat& disparity, double inlier_threshold);

// Boundary types between neighbouring superpixels (Eq. 5, after SPS-Stereo).
enum class BoundaryType { kOcclusion, kHinge, kCoplanar };

struct BoundaryTypeCounts {
  int occlusion = 0;
  int hinge = 0;
  int coplanar = 0;
};

// The plane step of the block-coordinate descent: `plane_iterations` rounds of (a) choosing each boundary's type
// as the cheapest of occlusion / hinge / coplanar and (b) re-fitting every plane to its inlier disparities
// (weight lambda_d / range^2) plus, for hinge and coplanar neighbours, agreement with the neighbour's plane on the
// shared boundary or on both superpixels (weight lambda_s, Eq. 5). Planes are updated in place (Gauss-Seidel).
BoundaryTypeCounts SmoothPlanes(const cv::Mat& labels, int count, const cv::Mat& disparity, double disparity_range,
                                const LfspParams& params, std::vector<Plane>& planes);

}  // namespace lfsp::segment
