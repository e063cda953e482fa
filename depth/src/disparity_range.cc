#include "lfsp/depth/disparity_range.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/ordered_reduction.h"
#include "lfsp/core/registration.h"

namespace lfsp::depth {
namespace {

constexpr double kStep = 0.05;             // px per view step between swept disparities
constexpr double kMaxSearch = 8.0;         // px per view step: beyond any lenslet or HCI light field
constexpr int kHalveAbove = 256;           // views wider than this are halved first (noise, speed)
constexpr int kWindow = 7;                 // cost aggregation window, px (on the possibly halved image)
constexpr double kClearMinimum = 0.5;      // a winner counts when its cost is below this fraction of the mean
constexpr double kTexturedQuantile = 0.5;  // ... and the centre's gradient energy is above this quantile
constexpr double kMinUsedFraction = 0.01;
constexpr double kTail = 0.02;  // the range spans the winners from this quantile to its complement

struct SweepView {
  cv::Mat grey;  // CV_32F, possibly halved
  double du = 0.0, dv = 0.0;
};

cv::Mat PreparedGrey(const cv::Mat& rgb, double scale) {
  cv::Mat grey = GreyOf(rgb);
  if (scale != 1.0) cv::resize(grey, grey, cv::Size(), scale, scale, cv::INTER_AREA);
  return grey;
}

double Quantile(std::vector<float> values, double q) {
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[static_cast<std::size_t>(k)];
}

}  // namespace

RangeEstimate EstimateDisparityRange(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  if (light_field.empty() || shape.channels != 3) throw Error("disparity range: need a light field of RGB views");
  const ViewIndex c = shape.Centre();
  const int offset = std::max(1, static_cast<int>(std::lround((std::min(shape.nu, shape.nv) - 1) / 3.0)));
  if (shape.nu < 2 && shape.nv < 2) throw Error("disparity range: a single view has no disparity");
  const double scale = shape.width > kHalveAbove ? 0.5 : 1.0;

  const cv::Mat centre = PreparedGrey(light_field.View(c), scale);
  std::vector<SweepView> views;
  for (const auto& [du, dv] :
       {std::pair{-offset, 0}, std::pair{offset, 0}, std::pair{0, -offset}, std::pair{0, offset}}) {
    const ViewIndex view{c.u + du, c.v + dv};
    if (view.u < 0 || view.v < 0 || view.u >= shape.nu || view.v >= shape.nv) continue;
    views.push_back({PreparedGrey(light_field.View(view), scale), static_cast<double>(du), static_cast<double>(dv)});
  }

  RangeEstimate estimate;
  estimate.searched = std::min(kMaxSearch, 0.25 * shape.width / offset);
  const int levels = static_cast<int>(std::floor(estimate.searched / kStep)) * 2 + 1;
  const cv::Size size = centre.size();
  // Per pixel: the lowest aggregated cost, its level, and the sum over levels (for the mean). Levels are swept in
  // parallel and summed in a fixed order (OrderedParallelSum), so the cost volume itself is never held and the
  // estimate is the same on every run; ties keep the lower level, as a serial sweep would.
  struct Partial {
    cv::Mat best, level, sum;
    cv::Mat aggregated, warped, difference;  // scratch
  };
  const auto make_partial = [&] {
    return Partial{cv::Mat(size, CV_32F, cv::Scalar(std::numeric_limits<float>::max())),
                   cv::Mat(size, CV_32S, cv::Scalar(0)),
                   cv::Mat::zeros(size, CV_32F),
                   {},
                   {},
                   {}};
  };
  const auto sweep_level = [&](int level, Partial& partial) {
    const double d = (level - (levels - 1) / 2) * kStep;  // px per view step, full resolution
    // Each view's difference aggregated on its own; the pixel's cost is the sum of the two best views, so that
    // a view in which an occluder hides the pixel does not decide (the coarse version of the depth stage's
    // half-patch choice).
    std::vector<cv::Mat> per_view;
    for (const SweepView& view : views) {
      // The centre pixel x at disparity d is seen in view (du, dv) at x - du * d (docs/DESIGN.md convention).
      const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -view.du * d * scale, 0, 1, -view.dv * d * scale);
      cv::warpAffine(view.grey, partial.warped, shift, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                     cv::BORDER_REPLICATE);
      cv::absdiff(partial.warped, centre, partial.difference);
      per_view.emplace_back();
      cv::blur(partial.difference, per_view.back(), cv::Size(kWindow, kWindow));
    }
    partial.aggregated.create(size, CV_32F);
    for (int y = 0; y < size.height; ++y) {
      float* out = partial.aggregated.ptr<float>(y);
      for (int x = 0; x < size.width; ++x) {
        float lowest = std::numeric_limits<float>::max(), second = lowest;
        for (const cv::Mat& cost : per_view) {
          const float value = cost.ptr<float>(y)[x];
          if (value < lowest) {
            second = lowest;
            lowest = value;
          } else if (value < second) {
            second = value;
          }
        }
        out[x] = per_view.size() > 1 ? lowest + second : lowest;
      }
    }
    partial.sum += partial.aggregated;
    for (int y = 0; y < size.height; ++y) {
      const float* a = partial.aggregated.ptr<float>(y);
      float* b = partial.best.ptr<float>(y);
      int* l = partial.level.ptr<int>(y);
      for (int x = 0; x < size.width; ++x)
        if (a[x] < b[x]) {
          b[x] = a[x];
          l[x] = level;
        }
    }
  };
  const auto merge = [&](Partial& into, const Partial& from) {
    into.sum += from.sum;
    for (int y = 0; y < size.height; ++y)
      for (int x = 0; x < size.width; ++x)
        if (from.best.at<float>(y, x) < into.best.at<float>(y, x)) {
          into.best.at<float>(y, x) = from.best.at<float>(y, x);
          into.level.at<int>(y, x) = from.level.at<int>(y, x);
        }
  };
  const Partial swept = OrderedParallelSum(levels, make_partial, sweep_level, merge);
  const cv::Mat& best_cost = swept.best;
  const cv::Mat& best_level = swept.level;
  const cv::Mat& cost_sum = swept.sum;

  // Texture: gradient energy of the centre, aggregated like the cost.
  cv::Mat gx, gy, energy;
  cv::Sobel(centre, gx, CV_32F, 1, 0);
  cv::Sobel(centre, gy, CV_32F, 0, 1);
  cv::blur(gx.mul(gx) + gy.mul(gy), energy, cv::Size(kWindow, kWindow));
  std::vector<float> energies(energy.begin<float>(), energy.end<float>());
  const double textured = Quantile(energies, kTexturedQuantile);

  std::vector<float> winners;
  const int margin = kWindow;  // the replicated border decides nothing
  for (int y = margin; y < size.height - margin; ++y)
    for (int x = margin; x < size.width - margin; ++x) {
      if (energy.at<float>(y, x) <= textured) continue;
      const int best = best_level.at<int>(y, x);
      if (best == 0 || best == levels - 1) continue;  // at the sweep's end: not a measurement
      if (best_cost.at<float>(y, x) >= kClearMinimum * cost_sum.at<float>(y, x) / levels) continue;
      winners.push_back(static_cast<float>((best - (levels - 1) / 2) * kStep));
    }
  estimate.pixels_used = static_cast<int>(winners.size());
  if (winners.size() < kMinUsedFraction * static_cast<double>(size.area()) || winners.size() < 20)
    throw Error("disparity range: the views are too flat to measure their disparity (" +
                std::to_string(winners.size()) + " usable pixels); give " + OptionName("dmin") + "/" +
                OptionName("dmax"));
  estimate.measured = {static_cast<float>(Quantile(winners, kTail)),
                       static_cast<float>(Quantile(winners, 1.0 - kTail))};
  const float pad = 0.1f * (estimate.measured.max - estimate.measured.min) + 0.1f;
  estimate.range = {estimate.measured.min - pad, estimate.measured.max + pad};
  return estimate;
}

}  // namespace lfsp::depth
