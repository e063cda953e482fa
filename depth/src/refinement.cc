#include "lfsp/depth/refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

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
  if (guide_rgb.type() != CV_32FC3 || guide_rgb.rows != disparity.height() || guide_rgb.cols != disparity.width()) {
    throw Error("weighted median: the guide must be a float RGB image of the disparity map's size");
  }
  // Our own implementation: OpenCV's ximgproc::weightedMedianFilter was measured to give different results on
  // repeated calls in one process, and results must be reproducible.
  const DisparityMap source = disparity;
  const float inverse = 1.0f / (2.0f * sigma * sigma);
  const int width = disparity.width();
  const int height = disparity.height();
#pragma omp parallel
  {
    std::vector<std::pair<float, float>> samples;  // (disparity, weight)
#pragma omp for schedule(static)
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const cv::Vec3f centre = guide_rgb.at<cv::Vec3f>(y, x);
        samples.clear();
        float total = 0.0f;
        for (int yy = std::max(0, y - radius); yy <= std::min(height - 1, y + radius); ++yy) {
          const cv::Vec3f* row = guide_rgb.ptr<cv::Vec3f>(yy);
          for (int xx = std::max(0, x - radius); xx <= std::min(width - 1, x + radius); ++xx) {
            const cv::Vec3f difference = row[xx] - centre;
            const float weight = std::exp(-difference.dot(difference) * inverse);
            samples.emplace_back(source.at(yy, xx), weight);
            total += weight;
          }
        }
        std::sort(samples.begin(), samples.end());
        float cumulative = 0.0f;
        for (const auto& [value, weight] : samples) {
          cumulative += weight;
          if (cumulative >= 0.5f * total) {
            disparity.at(y, x) = value;
            break;
          }
        }
      }
    }
  }
}

}  // namespace lfsp::depth
