#include "lfsp/depth/region_metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "evaluation_checks.h"
#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"

namespace lfsp::depth {
namespace {

// d/dx and d/dy of a CV_64F map with the normalised Scharr operator: (3, 10, 3) / 16 across, (1, 0, -1) / 2 along,
// a central difference of a slightly smoothed map. Borders replicate (the evaluation frame ignores them anyway).
cv::Mat ScharrX(const cv::Mat& map) {
  cv::Mat out;
  cv::Scharr(map, out, CV_64F, 1, 0, 1.0 / 32.0, 0.0, cv::BORDER_REPLICATE);
  return out;
}
cv::Mat ScharrY(const cv::Mat& map) {
  cv::Mat out;
  cv::Scharr(map, out, CV_64F, 0, 1, 1.0 / 32.0, 0.0, cv::BORDER_REPLICATE);
  return out;
}

// |H|_F of a CV_64F map, per pixel, each second derivative a derivative of a first one (as the benchmark does).
cv::Mat HessianNorm(const cv::Mat& map) {
  const cv::Mat dx = ScharrX(map);
  const cv::Mat dy = ScharrY(map);
  const cv::Mat dxx = ScharrX(dx), dxy = ScharrY(dx), dyy = ScharrY(dy), dyx = ScharrX(dy);
  cv::Mat norm = dxx.mul(dxx) + dxy.mul(dxy) + dyy.mul(dyy) + dyx.mul(dyx);
  cv::sqrt(norm, norm);
  return norm;
}

cv::Mat AsDouble(const DisparityMap& map) {
  cv::Mat out;
  map.Mat().convertTo(out, CV_64F);
  return out;
}

void CheckInputs(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region) {
  CheckSameSize(algo, gt);
  CheckRegion(gt, region);
}

// Calls visit(y, x) for every pixel of `region` inside the evaluation frame.
template <typename Visit>
void ForEachEvaluated(const cv::Mat& region, int boundary, Visit visit) {
  const cv::Mat inside = BoundaryMask(region.cols, region.rows, boundary);
  for (int y = 0; y < region.rows; ++y)
    for (int x = 0; x < region.cols; ++x)
      if (inside.at<unsigned char>(y, x) != 0 && region.at<unsigned char>(y, x) != 0) visit(y, x);
}

// A mask file reduced to the ground truth's size: any pixel of a block (`any`) or all of them.
cv::Mat MaskFromFile(const std::filesystem::path& path, int width, int height, bool any) {
  const ImageFile file = ReadImage(path);
  cv::Mat first;
  cv::extractChannel(file.pixels, first, 0);
  cv::Mat inside = first > 0.0f;
  if (inside.cols == width && inside.rows == height) return inside;
  const int factor = inside.cols / width;
  if (factor < 1 || inside.cols != factor * width || inside.rows != factor * height)
    throw Error(path.string() + ": mask is " + std::to_string(inside.cols) + "x" + std::to_string(inside.rows) +
                ", not the ground truth's " + std::to_string(width) + "x" + std::to_string(height) +
                " or an integer multiple of it");
  cv::Mat reduced(height, width, CV_8U);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const cv::Mat block = inside(cv::Rect(x * factor, y * factor, factor, factor));
      const int count = cv::countNonZero(block);
      reduced.at<unsigned char>(y, x) = (any ? count > 0 : count == factor * factor) ? 255 : 0;
    }
  return reduced;
}

}  // namespace

EvaluationMasks DeriveEvaluationMasks(const DisparityMap& gt, const MetricOptions& options,
                                      const MaskOptions& mask_options) {
  if (gt.empty()) throw Error("depth evaluation: empty ground truth");
  EvaluationMasks masks;
  masks.discontinuities = DiscontinuityRegion(gt, options.discontinuity_jump, options.discontinuity_radius);
  const cv::Mat truth = AsDouble(gt);
  cv::Mat finite = truth == truth;  // NaN != NaN
  cv::Mat infinite = cv::abs(truth) == std::numeric_limits<double>::infinity();
  finite.setTo(0, infinite);
  cv::Mat safe = truth.clone();
  safe.setTo(0.0, finite == 0);
  const cv::Mat curvature = HessianNorm(safe);
  // A pixel whose Hessian stencil (5 x 5: two 3 x 3 operators) reaches a non-finite value is in neither region.
  cv::Mat stencil_finite;
  cv::erode(finite, stencil_finite, cv::Mat::ones(5, 5, CV_8U));
  const cv::Mat surface = stencil_finite & (masks.discontinuities == 0);
  masks.planes = surface & (curvature < mask_options.plane_curvature);
  masks.smooth_surfaces = surface & (curvature >= mask_options.plane_curvature);
  masks.discontinuities_source = masks.planes_source = masks.smooth_surfaces_source = "derived from the ground truth";
  return masks;
}

EvaluationMasks ReadEvaluationMasks(const std::filesystem::path& folder, const DisparityMap& gt,
                                    const MetricOptions& options, const MaskOptions& mask_options) {
  EvaluationMasks masks = DeriveEvaluationMasks(gt, options, mask_options);
  const auto replace = [&](const char* name, bool any, cv::Mat& mask, std::string& source) {
    const std::filesystem::path path = folder / name;
    if (!std::filesystem::exists(path)) return;
    mask = MaskFromFile(path, gt.width(), gt.height(), any);
    source = "file " + path.string();
  };
  replace("mask_discontinuities.png", true, masks.discontinuities, masks.discontinuities_source);
  replace("mask_planes.png", false, masks.planes, masks.planes_source);
  replace("mask_smooth_surfaces.png", false, masks.smooth_surfaces, masks.smooth_surfaces_source);
  return masks;
}

double Bumpiness(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary) {
  CheckInputs(algo, gt, region);
  constexpr double kClip = 0.05;
  const cv::Mat norm = HessianNorm(AsDouble(algo) - AsDouble(gt));
  double sum = 0.0;
  std::size_t count = 0;
  ForEachEvaluated(region, boundary, [&](int y, int x) {
    const double value = norm.at<double>(y, x);
    if (!std::isfinite(value)) return;
    sum += std::min(kClip, value);
    ++count;
  });
  return count == 0 ? std::nan("") : 100.0 * sum / static_cast<double>(count);
}

double FatteningIndex(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary) {
  CheckInputs(algo, gt, region);
  std::size_t bad = 0, nearer = 0;
  ForEachEvaluated(region, boundary, [&](int y, int x) {
    const float difference = algo.at(y, x) - gt.at(y, x);
    if (!(std::abs(difference) > 0.07f)) return;  // as BadPix 0.07: NaN is never bad
    ++bad;
    if (difference > 0.0f) ++nearer;
  });
  return bad == 0 ? std::nan("") : 100.0 * static_cast<double>(nearer) / static_cast<double>(bad);
}

Sparsification SparsificationOf(const DisparityMap& algo, const DisparityMap& gt, const DisparityMap& confidence,
                                int boundary) {
  const cv::Mat everything(gt.height(), gt.width(), CV_8U, cv::Scalar(255));
  CheckInputs(algo, gt, everything);
  if (confidence.width() != gt.width() || confidence.height() != gt.height())
    throw Error("depth evaluation: the confidence map is " + std::to_string(confidence.width()) + "x" +
                std::to_string(confidence.height()) + " but the ground truth is " + std::to_string(gt.width()) + "x" +
                std::to_string(gt.height()));
  struct Pixel {
    double confidence;
    double squared_error;
  };
  std::vector<Pixel> pixels;
  ForEachEvaluated(everything, boundary, [&](int y, int x) {
    const double error = static_cast<double>(algo.at(y, x)) - static_cast<double>(gt.at(y, x));
    const double c = confidence.at(y, x);
    if (std::isfinite(error)) pixels.push_back({std::isfinite(c) ? c : -1e300, error * error});
  });
  Sparsification result;
  if (pixels.empty()) {
    result.area = result.oracle_area = result.area_between = std::nan("");
    return result;
  }
  // MSE x100 of the first p % of `order` for p = 1 ... 100 (at least one pixel each).
  const auto curve_of = [&](const std::vector<Pixel>& order) {
    std::vector<double> prefix(order.size() + 1, 0.0);
    for (std::size_t i = 0; i < order.size(); ++i) prefix[i + 1] = prefix[i] + order[i].squared_error;
    std::vector<double> curve;
    for (int p = 1; p <= 100; ++p) {
      const std::size_t n = std::max<std::size_t>(1, order.size() * static_cast<std::size_t>(p) / 100);
      curve.push_back(100.0 * prefix[n] / static_cast<double>(n));
    }
    return curve;
  };
  std::vector<Pixel> by_confidence = pixels;
  // Ties keep the image order, so the result does not depend on the sort's implementation.
  std::stable_sort(by_confidence.begin(), by_confidence.end(),
                   [](const Pixel& a, const Pixel& b) { return a.confidence > b.confidence; });
  std::vector<Pixel> by_error = std::move(pixels);
  std::stable_sort(by_error.begin(), by_error.end(),
                   [](const Pixel& a, const Pixel& b) { return a.squared_error < b.squared_error; });
  result.curve = curve_of(by_confidence);
  result.oracle = curve_of(by_error);
  const auto mean = [](const std::vector<double>& values) {
    return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
  };
  result.area = mean(result.curve);
  result.oracle_area = mean(result.oracle);
  result.area_between = result.area - result.oracle_area;
  return result;
}

}  // namespace lfsp::depth
