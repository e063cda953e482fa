#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"
#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

// How strongly the raw (unaggregated) data supports the chosen disparity of each pixel:
// (mean over labels of the cost - cost at the chosen label) / mean cost, in [0, 1]. Textureless pixels (flat cost
// curve) score ~0 even where semi-global aggregation has filled in a confident-looking value.
DisparityMap DataSupport(const CostVolume& raw_cost, const DisparityMap& disparity, const std::vector<float>& labels);

struct PlaneFitOptions {
  int region_size = 16;              // SLIC superpixel size on the centre view, pixels
  float support_threshold = 0.5f;    // DataSupport above this: a pixel the plane is fitted to
  float inlier_distance = 0.05f;     // px/view: a supporting pixel within this of the plane is an inlier
  float min_inlier_fraction = 0.6f;  // of the supporting pixels, for the plane to be trusted
  int min_support = 12;              // supporting pixels needed in a superpixel
};

// Slanted-plane refinement: in each superpixel of the centre view, fits a plane d = a x + b y + c (iteratively
// reweighted least squares) to the pixels the data supports and gives the plane's value to the unsupported ones.
// Semi-global aggregation fills textureless areas fronto-parallel, which is wrong on slanted surfaces (floors).
void PlaneFitRefine(DisparityMap& disparity, const DisparityMap& support, const cv::Mat& guide_rgb,
                    const PlaneFitOptions& options);

}  // namespace lfsp::depth
