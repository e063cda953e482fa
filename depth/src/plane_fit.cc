#include "lfsp/depth/plane_fit.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <vector>

#include "lfsp/core/plane_fit.h"

namespace lfsp::depth {

DisparityMap DataSupport(const CostVolume& raw_cost, const DisparityMap& disparity, const std::vector<float>& labels) {
  DisparityMap support(disparity.width(), disparity.height(), 0.0f);
  const int count = raw_cost.labels();
  const float step = labels[1] - labels[0];
#pragma omp parallel for schedule(static)
  for (int y = 0; y < disparity.height(); ++y) {
    for (int x = 0; x < disparity.width(); ++x) {
      const float* curve = raw_cost.Curve(y, x);
      const int l = std::clamp(static_cast<int>(std::lround((disparity.at(y, x) - labels[0]) / step)), 0, count - 1);
      double mean = 0.0;
      for (int k = 0; k < count; ++k) mean += curve[k];
      mean /= count;
      support.at(y, x) = mean > 0.0 ? static_cast<float>(std::clamp((mean - curve[l]) / mean, 0.0, 1.0)) : 0.0f;
    }
  }
  return support;
}

namespace {

struct Plane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double At(int x, int y) const { return a * x + b * y + c; }
};

// Weighted least squares (the shared fit of lfsp/core/plane_fit.h) with Huber-style reweighting: a few outliers (wrong
// matches) do not tilt the plane.
bool FitPlane(const std::vector<cv::Point>& points, const DisparityMap& disparity, float inlier_distance,
              Plane& plane) {
  if (points.size() < 3) return false;
  std::vector<double> weights(points.size(), 1.0);
  for (int iteration = 0; iteration < 4; ++iteration) {
    PlaneSums sums;
    for (std::size_t i = 0; i < points.size(); ++i)
      sums.Add(points[i].x, points[i].y, disparity.at(points[i].y, points[i].x), weights[i]);
    cv::Vec3d solution;
    if (!SolvePlane(sums.m, sums.r, solution)) return false;
    plane = {solution[0], solution[1], solution[2]};
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double residual = std::abs(disparity.at(points[i].y, points[i].x) - plane.At(points[i].x, points[i].y));
      weights[i] = residual <= inlier_distance ? 1.0 : inlier_distance / residual;
    }
  }
  return true;
}

}  // namespace

void PlaneFitRefine(DisparityMap& disparity, const DisparityMap& support, const cv::Mat& guide_rgb,
                    const PlaneFitOptions& options) {
  cv::Mat guide8;
  guide_rgb.convertTo(guide8, CV_8UC3, 255.0);
  cv::Mat lab;
  cv::cvtColor(guide8, lab, cv::COLOR_RGB2Lab);
  cv::Ptr<cv::ximgproc::SuperpixelSLIC> slic =
      cv::ximgproc::createSuperpixelSLIC(lab, cv::ximgproc::SLICO, options.region_size);
  slic->iterate(5);
  cv::Mat labels;
  slic->getLabels(labels);
  const int regions = slic->getNumberOfSuperpixels();

  std::vector<std::vector<cv::Point>> supported(static_cast<std::size_t>(regions));
  std::vector<std::vector<cv::Point>> unsupported(static_cast<std::size_t>(regions));
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const auto r = static_cast<std::size_t>(labels.at<int>(y, x));
      (support.at(y, x) >= options.support_threshold ? supported[r] : unsupported[r]).emplace_back(x, y);
    }
  }
#pragma omp parallel for schedule(dynamic)
  for (int r = 0; r < regions; ++r) {
    const auto& points = supported[static_cast<std::size_t>(r)];
    if (static_cast<int>(points.size()) < options.min_support) continue;
    Plane plane;
    if (!FitPlane(points, disparity, options.inlier_distance, plane)) continue;
    std::size_t inliers = 0;
    for (const cv::Point& p : points) {
      if (std::abs(disparity.at(p.y, p.x) - plane.At(p.x, p.y)) <= options.inlier_distance) ++inliers;
    }
    if (static_cast<float>(inliers) < options.min_inlier_fraction * static_cast<float>(points.size())) continue;
    for (const cv::Point& p : unsupported[static_cast<std::size_t>(r)]) {
      disparity.at(p.y, p.x) = static_cast<float>(plane.At(p.x, p.y));
    }
  }
}

}  // namespace lfsp::depth
