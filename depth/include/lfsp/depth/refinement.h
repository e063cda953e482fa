#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

struct DisparityEstimate {
  DisparityMap disparity;
  DisparityMap confidence;  // in [0, 1]: how clearly the best label beats the best label not adjacent to it
};

// Winner-take-all per pixel, refined below the label step by fitting a parabola through the best label's cost and
// its two neighbours. Confidence = (c_other - c_best) / c_other, c_other being the lowest cost more than one label
// away from the best.
DisparityEstimate SelectDisparity(const CostVolume& cost, const std::vector<float>& disparities);

// Weighted median of the disparity in a (2 radius + 1)^2 window, weights exp(-|colour difference|^2 / (2 sigma^2))
// from the centre view, which removes isolated outliers while keeping depth edges on colour edges.
void WeightedMedianRefine(DisparityMap& disparity, const cv::Mat& guide_rgb, int radius, float sigma);

}  // namespace lfsp::depth
