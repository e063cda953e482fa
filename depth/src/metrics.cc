#include "lfsp/depth/metrics.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "evaluation_checks.h"
#include "lfsp/core/error.h"
#include "lfsp/depth/region_metrics.h"

namespace lfsp::depth {
namespace {

double Percentage(std::size_t total, std::size_t part) {
  return total == 0 ? std::nan("") : 100.0 * static_cast<double>(part) / static_cast<double>(total);
}

}  // namespace

cv::Mat BoundaryMask(int width, int height, int boundary) {
  cv::Mat mask(height, width, CV_8U, cv::Scalar(0));
  if (width > 2 * boundary && height > 2 * boundary) {
    mask(cv::Rect(boundary, boundary, width - 2 * boundary, height - 2 * boundary)).setTo(255);
  }
  return mask;
}

cv::Mat DistanceToDisparityJumps(const DisparityMap& map, double jump) {
  const int w = map.width();
  const int h = map.height();
  // Both pixels of a jump are marked with 0 for cv::distanceTransform, everything else 255.
  cv::Mat not_jump(h, w, CV_8U, cv::Scalar(255));
  auto mark_step = [&](int y0, int x0, int y1, int x1) {
    const float a = map.at(y0, x0);
    const float b = map.at(y1, x1);
    if (std::isfinite(a) && std::isfinite(b) && std::abs(a - b) > jump) {
      not_jump.at<unsigned char>(y0, x0) = 0;
      not_jump.at<unsigned char>(y1, x1) = 0;
    }
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) mark_step(y, x, y, x + 1);
      if (y + 1 < h) mark_step(y, x, y + 1, x);
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_jump, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance;
}

cv::Mat DiscontinuityRegion(const DisparityMap& gt, double jump, double radius) {
  cv::Mat region;
  cv::compare(DistanceToDisparityJumps(gt, jump), radius, region, cv::CMP_LE);
  return region;
}

DepthMetrics ComputeMetrics(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary) {
  CheckSameSize(algo, gt);
  CheckRegion(gt, region);
  const cv::Mat inside = BoundaryMask(gt.width(), gt.height(), boundary);
  DepthMetrics metrics;
  double squared_sum = 0.0;
  std::size_t squared_count = 0;
  std::size_t bad_007 = 0;
  std::size_t bad_003 = 0;
  std::size_t bad_001 = 0;
  std::vector<float> scaled_errors;  // 100 * |algo - gt|, for Q25
  for (int y = 0; y < gt.height(); ++y) {
    for (int x = 0; x < gt.width(); ++x) {
      if (inside.at<unsigned char>(y, x) == 0 || region.at<unsigned char>(y, x) == 0) continue;
      const float a = algo.at(y, x);
      const float g = gt.at(y, x);
      // float arithmetic as in the toolkit (float32 arrays); NaN compares false, so it is never bad.
      const float difference = std::abs(a - g);
      ++metrics.pixels;
      if (difference > 0.07f) ++bad_007;
      if (difference > 0.03f) ++bad_003;
      if (difference > 0.01f) ++bad_001;
      if (std::isfinite(a) && std::isfinite(g)) {
        const double d = static_cast<double>(g) - static_cast<double>(a);
        squared_sum += d * d;
        ++squared_count;
      }
      const float scaled = difference * 100.0f;
      if (std::isfinite(scaled) && std::isfinite(a)) scaled_errors.push_back(scaled);
    }
  }
  metrics.mse_x100 = squared_count == 0 ? std::nan("") : 100.0 * squared_sum / static_cast<double>(squared_count);
  metrics.badpix_007 = Percentage(metrics.pixels, bad_007);
  metrics.badpix_003 = Percentage(metrics.pixels, bad_003);
  metrics.badpix_001 = Percentage(metrics.pixels, bad_001);
  if (scaled_errors.empty()) {
    metrics.q25 = std::nan("");
  } else {
    const auto index = static_cast<std::size_t>(static_cast<double>(scaled_errors.size()) * 25.0 / 100.0);
    std::nth_element(scaled_errors.begin(), scaled_errors.begin() + static_cast<std::ptrdiff_t>(index),
                     scaled_errors.end());
    metrics.q25 = scaled_errors[index];
  }
  return metrics;
}

DepthEvaluation EvaluateDisparity(const DisparityMap& algo, const DisparityMap& gt, const MetricOptions& options) {
  CheckSameSize(algo, gt);
  return EvaluateDisparity(algo, gt, options, DeriveEvaluationMasks(gt, options));
}

DepthEvaluation EvaluateDisparity(const DisparityMap& algo, const DisparityMap& gt, const MetricOptions& options,
                                  const EvaluationMasks& masks, const DisparityMap* confidence) {
  CheckSameSize(algo, gt);
  DepthEvaluation evaluation;
  evaluation.options = options;
  const cv::Mat everything(gt.height(), gt.width(), CV_8U, cv::Scalar(255));
  evaluation.all = ComputeMetrics(algo, gt, everything, options.boundary);
  evaluation.near_discontinuities = ComputeMetrics(algo, gt, masks.discontinuities, options.boundary);
  evaluation.fattening_all = FatteningIndex(algo, gt, everything, options.boundary);
  evaluation.fattening_near_discontinuities = FatteningIndex(algo, gt, masks.discontinuities, options.boundary);
  evaluation.bumpiness_planes = Bumpiness(algo, gt, masks.planes, options.boundary);
  evaluation.bumpiness_smooth_surfaces = Bumpiness(algo, gt, masks.smooth_surfaces, options.boundary);
  const cv::Mat inside = BoundaryMask(gt.width(), gt.height(), options.boundary);
  evaluation.plane_pixels = static_cast<std::size_t>(cv::countNonZero(masks.planes & inside));
  evaluation.smooth_surface_pixels = static_cast<std::size_t>(cv::countNonZero(masks.smooth_surfaces & inside));
  evaluation.discontinuities_source = masks.discontinuities_source;
  evaluation.planes_source = masks.planes_source;
  evaluation.smooth_surfaces_source = masks.smooth_surfaces_source;
  if (confidence != nullptr) evaluation.sparsification = SparsificationOf(algo, gt, *confidence, options.boundary);
  return evaluation;
}

nlohmann::json ToJson(const DepthMetrics& metrics) {
  // JSON has no NaN: an empty region reports null.
  auto number = [](double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); };
  return {{"mse_x100", number(metrics.mse_x100)},
          {"badpix_0.07", number(metrics.badpix_007)},
          {"badpix_0.03", number(metrics.badpix_003)},
          {"badpix_0.01", number(metrics.badpix_001)},
          {"q25", number(metrics.q25)},
          {"pixels", metrics.pixels}};
}

nlohmann::json ToJson(const DepthEvaluation& evaluation) {
  auto number = [](double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); };
  nlohmann::json json = {{"all", ToJson(evaluation.all)},
                         {"near_discontinuities", ToJson(evaluation.near_discontinuities)},
                         {"fattening_index",
                          {{"all", number(evaluation.fattening_all)},
                           {"near_discontinuities", number(evaluation.fattening_near_discontinuities)}}},
                         {"bumpiness",
                          {{"planes", number(evaluation.bumpiness_planes)},
                           {"smooth_surfaces", number(evaluation.bumpiness_smooth_surfaces)},
                           {"plane_pixels", evaluation.plane_pixels},
                           {"smooth_surface_pixels", evaluation.smooth_surface_pixels}}},
                         {"definition",
                          {{"boundary_px", evaluation.options.boundary},
                           {"discontinuity_jump_px", evaluation.options.discontinuity_jump},
                           {"discontinuity_radius_px", evaluation.options.discontinuity_radius},
                           {"masks",
                            {{"discontinuities", evaluation.discontinuities_source},
                             {"planes", evaluation.planes_source},
                             {"smooth_surfaces", evaluation.smooth_surfaces_source}}}}}};
  if (evaluation.sparsification) {
    const Sparsification& s = *evaluation.sparsification;
    json["sparsification"] = {{"area_mse_x100", number(s.area)},
                              {"oracle_area_mse_x100", number(s.oracle_area)},
                              {"area_between", number(s.area_between)},
                              {"curve_mse_x100", s.curve},
                              {"oracle_mse_x100", s.oracle}};
  }
  return json;
}

}  // namespace lfsp::depth
