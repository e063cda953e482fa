#include "lfsp/depth/refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "lfsp/core/error.h"

namespace lfsp::depth {

DisparityEstimate SelectDisparity(const CostVolume& cost, const std::vector<float>& disparities) {
  const int labels = cost.labels();
  if (static_cast<int>(disparities.size()) != labels) throw Error("depth: label count differs from the cost volume");
  const float step = labels > 1 ? disparities[1] - disparities[0] : 0.0f;
  DisparityEstimate estimate{DisparityMap(cost.width(), cost.height()), DisparityMap(cost.width(), cost.height())};
#pragma omp parallel for schedule(static)
  for (int y = 0; y < cost.height(); ++y) {
    for (int x = 0; x < cost.width(); ++x) {
      const float* curve = cost.Curve(y, x);
      const int best = static_cast<int>(std::min_element(curve, curve + labels) - curve);
      float offset = 0.0f;
      if (best > 0 && best + 1 < labels) {
        const float curvature = curve[best - 1] - 2.0f * curve[best] + curve[best + 1];
        if (curvature > 0.0f) offset = std::clamp(0.5f * (curve[best - 1] - curve[best + 1]) / curvature, -0.5f, 0.5f);
      }
      estimate.disparity.at(y, x) = disparities[static_cast<std::size_t>(best)] + offset * step;
      float other = std::numeric_limits<float>::max();
      for (int l = 0; l < labels; ++l) {
        if (std::abs(l - best) > 1) other = std::min(other, curve[l]);
      }
      estimate.confidence.at(y, x) =
          other > 0.0f && other < std::numeric_limits<float>::max() ? (other - curve[best]) / other : 0.0f;
    }
  }
  return estimate;
}

void WeightedMedianRefine(DisparityMap& disparity, const cv::Mat& guide_rgb, int radius, float sigma) {
  if (radius <= 0) return;
  cv::Mat guide8;
  guide_rgb.convertTo(guide8, CV_8UC3, 255.0);
  cv::Mat filtered;
  cv::ximgproc::weightedMedianFilter(guide8, disparity.Mat(), filtered, radius, sigma * 255.0f);
  filtered.copyTo(disparity.Mat());
}

}  // namespace lfsp::depth
