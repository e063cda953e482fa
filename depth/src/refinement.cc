#include "lfsp/depth/refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/depth/sgm.h"

namespace lfsp::depth {

namespace {

// The wide window is read every second pixel (a quarter of the samples; the median of a patch of one colour hardly
// changes), and samples whose colour weight is below this are left out of it (they hardly move its median, and
// sorting them is most of the cost).
constexpr int kWideStride = 2;
constexpr float kNegligibleWeight = 1e-3f;

// The weighted samples of `source` over the window of `radius` around (x, y), every `stride` pixels, each weighted
// by exp(-|colour difference to (x, y)|^2 * inverse). Samples lighter than `lightest` are left out (the centre has
// weight 1), and so are non-finite disparities (a NaN would break the sort's ordering). Returns their total weight.
float WindowSamples(const DisparityMap& source, const cv::Mat& guide_rgb, int x, int y, int radius, int stride,
                    float inverse, float lightest, std::vector<std::pair<float, float>>& samples) {
  const cv::Vec3f centre = guide_rgb.at<cv::Vec3f>(y, x);
  samples.clear();
  float total = 0.0f;
  radius = std::min(radius, std::max(source.width(), source.height()));  // y + radius cannot overflow
  // Start on the grid through (x, y), so the centre is always a sample.
  const int first_row = y - (std::min(radius, y) / stride) * stride;
  const int first_column = x - (std::min(radius, x) / stride) * stride;
  const int last_row = std::min(source.height() - 1, y + radius);
  const int last_column = std::min(source.width() - 1, x + radius);
  for (int yy = first_row; yy <= last_row; yy += stride) {
    const cv::Vec3f* row = guide_rgb.ptr<cv::Vec3f>(yy);
    for (int xx = first_column; xx <= last_column; xx += stride) {
      const cv::Vec3f difference = row[xx] - centre;
      const float weight = std::exp(-difference.dot(difference) * inverse);
      const float value = source.at(yy, xx);
      if (weight < lightest || !std::isfinite(value)) continue;
      samples.emplace_back(value, weight);
      total += weight;
    }
  }
  return total;
}

// The weighted median of the samples (sorted in place): the first value at which the cumulative weight reaches
// half the total; `fallback` if none does (only NaN weights: a guide with non-finite colours, or sigma 0).
float MedianOf(std::vector<std::pair<float, float>>& samples, float total, float fallback) {
  std::sort(samples.begin(), samples.end());
  float cumulative = 0.0f;
  for (const auto& [value, weight] : samples) {
    cumulative += weight;
    if (cumulative >= 0.5f * total) return value;
  }
  return fallback;
}

// Whether the samples' weighted median lies more than `threshold` from `value`: more than half their weight on one
// side beyond it. Settles most pixels without the sort.
bool MedianIsFar(const std::vector<std::pair<float, float>>& samples, float total, float value, float threshold) {
  float below = 0.0f, above = 0.0f;
  for (const auto& [sample, weight] : samples) {
    if (sample < value - threshold) below += weight;
    if (sample > value + threshold) above += weight;
  }
  return below >= 0.5f * total || above > 0.5f * total;
}

}  // namespace

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

void RefineSubLabelFromData(DisparityMap& disparity, const CostVolume& aggregated, const CostVolume& data,
                            const std::vector<float>& disparities, const cv::Mat& guide_rgb,
                            const SubLabelOptions& options) {
  if (options.radius <= 0) return;
  const int width = aggregated.width(), height = aggregated.height(), labels = aggregated.labels();
  if (data.width() != width || data.height() != height || data.labels() != labels || disparity.width() != width ||
      disparity.height() != height || static_cast<int>(disparities.size()) != labels)
    throw Error("sub-label refinement: the cost volumes, the disparity map and the labels differ in size");
  if (guide_rgb.type() != CV_32FC3 || guide_rgb.rows != height || guide_rgb.cols != width)
    throw Error("sub-label refinement: the guide must be a float RGB image of the disparity map's size");
  if (labels < 3) return;
  const float step = disparities[1] - disparities[0];
  const float inverse = 1.0f / (2.0f * options.sigma * options.sigma);
  const int radius = options.radius;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float* curve = aggregated.Curve(y, x);
      const int best = static_cast<int>(std::min_element(curve, curve + labels) - curve);
      if (best == 0 || best + 1 == labels) continue;
      // What the paths add to a neighbouring label beyond the pixel's own data (SemiGlobalPaths copies of it):
      // near saturation on either side, the aggregated curve there is the penalty's, not the neighbours' data.
      const float* own = data.Curve(y, x) + best;
      const float paths = static_cast<float>(SemiGlobalPaths());
      const float added_below = (curve[best - 1] - curve[best]) - paths * (own[-1] - own[0]);
      const float added_above = (curve[best + 1] - curve[best]) - paths * (own[1] - own[0]);
      const float saturated = options.saturation * paths * options.p1;
      if (!(added_below >= saturated || added_above >= saturated)) continue;
      const cv::Vec3f centre = guide_rgb.at<cv::Vec3f>(y, x);
      double below = 0.0, at = 0.0, above = 0.0;
      for (int yy = std::max(0, y - radius); yy <= std::min(height - 1, y + radius); ++yy) {
        const cv::Vec3f* row = guide_rgb.ptr<cv::Vec3f>(yy);
        for (int xx = std::max(0, x - radius); xx <= std::min(width - 1, x + radius); ++xx) {
          const cv::Vec3f difference = row[xx] - centre;
          const double weight = std::exp(-difference.dot(difference) * inverse);
          const float* q = data.Curve(yy, xx) + best;
          below += weight * q[-1];
          at += weight * q[0];
          above += weight * q[1];
        }
      }
      if (!(at <= below && at <= above)) continue;
      const double rise = std::max(below, above) - at;
      if (!(rise > 0.0)) continue;
      const double offset = std::clamp(0.5 * (below - above) / rise, -0.5, 0.5);
      disparity.at(y, x) = disparities[static_cast<std::size_t>(best)] + static_cast<float>(offset) * step;
    }
  }
}

void WeightedMedianRefine(DisparityMap& disparity, const cv::Mat& guide_rgb, const MedianOptions& options) {
  if (options.radius <= 0) return;
  if (guide_rgb.type() != CV_32FC3 || guide_rgb.rows != disparity.height() || guide_rgb.cols != disparity.width()) {
    throw Error("weighted median: the guide must be a float RGB image of the disparity map's size");
  }
  // Our own implementation: OpenCV's ximgproc::weightedMedianFilter was measured to give different results on
  // repeated calls in one process, and results must be reproducible.
  const DisparityMap source = disparity;
  const float inverse = 1.0f / (2.0f * options.sigma * options.sigma);
  const bool wide = options.wide_radius > options.radius;
  const int width = disparity.width();
  const int height = disparity.height();
#pragma omp parallel
  {
    std::vector<std::pair<float, float>> samples;  // (disparity, weight)
#pragma omp for schedule(static)
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        float total = WindowSamples(source, guide_rgb, x, y, options.radius, 1, inverse, 0.0f, samples);
        float value = MedianOf(samples, total, source.at(y, x));
        if (wide) {
          total = WindowSamples(source, guide_rgb, x, y, options.wide_radius, kWideStride, inverse, kNegligibleWeight,
                                samples);
          if (MedianIsFar(samples, total, value, options.wide_threshold)) {
            const float far = MedianOf(samples, total, value);
            if (std::abs(far - value) > options.wide_threshold) value = far;
          }
        }
        disparity.at(y, x) = value;
      }
    }
  }
}

void LowerConfidenceNearDepthEdges(DisparityMap& confidence, const DisparityMap& disparity,
                                   const EdgeConfidenceOptions& options) {
  const int w = disparity.width();
  const int h = disparity.height();
  if (confidence.width() != w || confidence.height() != h)
    throw Error("depth: the confidence map and the disparity differ in size");
  const cv::Mat distance = DistanceToDisparityJumps(disparity, options.jump);
  const float inverse = 1.0f / (2.0f * options.radius * options.radius);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float r = distance.at<float>(y, x);
      confidence.at(y, x) *= 1.0f - std::exp(-r * r * inverse);
    }
}

void RemoveConfidenceStreaks(DisparityMap& confidence) {
  if (confidence.width() < 3 || confidence.height() < 3) return;
  cv::Mat map = confidence.Mat(), filtered;
  for (int pass = 0; pass < 2; ++pass) {
    cv::medianBlur(map, filtered, 3);
    filtered.copyTo(map);  // back into the map's own memory
  }
}

}  // namespace lfsp::depth
