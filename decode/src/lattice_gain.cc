#include "lfsp/decode/lattice_gain.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "view_gain_common.h"

namespace lfsp::decode {
namespace {

constexpr int kBins = 16;  // per axis of the 2 x 2 px Bayer tile
static_assert(kBins * kBins <= 256, "a pixel's bin is kept in one byte");
// A view is compared with its own blur across lens rows only (Gaussian sigma, rows), the pixel's own row left out.
// Neighbouring lens rows fall on different parts of the Bayer tile, so the gain alternates from row to row while the
// scene's texture along a row cancels. A blur along rows as well (4 px) let texture whose period is near the bins'
// cycle along a row leak in: 0.19 % of gain measured, and put in, on a clean synthetic plane, against 0.04 % now.
constexpr double kReferenceSigmaRows = 2.0;
constexpr double kEdge = 0.1;            // pixels differing from the reference by more than this share: skipped
constexpr int kMinSamples = 20;          // a bin with fewer is not measured (it borrows from its neighbours)
constexpr double kBinSmoothing = 0.7;    // Gaussian sigma over the (periodic) bins
constexpr float kMinWeight = 0.02f;      // rays with less weight carry no usable light
constexpr double kMinMeanWeight = 0.05;  // views darker than this on average are left alone
constexpr double kMinLevel = 0.01;       // reference level below which the ratio is noise

int TilePhaseBin(double position) {
  const double phase = position - 2.0 * std::floor(0.5 * position);  // in [0, 2)
  return std::clamp(static_cast<int>(phase * 0.5 * kBins), 0, kBins - 1);
}

// For every decoded pixel, the bin of the sensor position of the lens nearest to where it is sampled (the slicing's
// Catmull-Rom mixes up to four lenses of the row; the nearest weighs most, and neighbouring lenses fall close on the
// tile: 0.07 px apart on an F01, 0.3 px on an Illum).
std::vector<std::uint8_t> LensBins(const HexLattice& lattice, int width, int height) {
  std::vector<std::uint8_t> bins(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  ForEachNearestLens(lattice, width, height, [&](int x, int y, double sx, double sy) {
    bins[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
        static_cast<std::uint8_t>(TilePhaseBin(sy) * kBins + TilePhaseBin(sx));
  });
  return bins;
}

// The reference each pixel is compared with: a Gaussian blur across rows without the pixel's own row.
cv::Mat ReferenceAcrossRows(const cv::Mat& grey) {
  const int taps = 2 * static_cast<int>(std::ceil(3.0 * kReferenceSigmaRows)) + 1;
  cv::Mat kernel = cv::getGaussianKernel(taps, kReferenceSigmaRows, CV_32F);
  kernel.at<float>(taps / 2) = 0.0f;
  kernel /= cv::sum(kernel)[0];
  cv::Mat reference;
  cv::sepFilter2D(grey, reference, CV_32F, cv::Mat::ones(1, 1, CV_32F), kernel, cv::Point(-1, -1), 0.0,
                  cv::BORDER_REFLECT);
  return reference;
}

// Smooths a kBins x kBins table over its periodic bins.
cv::Mat SmoothPeriodic(const cv::Mat& table) {
  const int pad = 3;
  cv::Mat padded, smoothed;
  cv::copyMakeBorder(table, padded, pad, pad, pad, pad, cv::BORDER_WRAP);
  cv::GaussianBlur(padded, smoothed, cv::Size(2 * pad + 1, 2 * pad + 1), kBinSmoothing, 0.0, cv::BORDER_REPLICATE);
  return smoothed(cv::Rect(pad, pad, kBins, kBins)).clone();
}

struct MeasuredGain {
  cv::Mat gain;               // kBins x kBins, CV_64F, mean 1 over the view's pixels
  std::vector<int> measured;  // bins with at least kMinSamples pixels
};

// The bins' gains in one view: mean ratio to the reference per bin, smoothed over the periodic bins as a normalised
// convolution (sparsely filled bins borrow from their neighbours instead of being pulled to 1), normalised so that
// the view keeps its brightness. Nothing when no bin is measured.
std::optional<MeasuredGain> MeasureGain(const cv::Mat& grey, const cv::Mat& weight,
                                        const std::vector<std::uint8_t>& bins) {
  const cv::Mat reference = ReferenceAcrossRows(grey);
  cv::Mat sum = cv::Mat::zeros(kBins, kBins, CV_64F), count = cv::Mat::zeros(kBins, kBins, CV_64F);
  auto* sums = sum.ptr<double>();
  auto* counts = count.ptr<double>();
  const int margin = static_cast<int>(std::ceil(3.0 * kReferenceSigmaRows));  // rows the blur reflects into
  for (int y = margin; y < grey.rows - margin; ++y) {
    const float* g = grey.ptr<float>(y);
    const float* r = reference.ptr<float>(y);
    const float* w = weight.ptr<float>(y);
    const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(grey.cols);
    for (int x = 0; x < grey.cols; ++x) {
      if (w[x] < kMinWeight || !(r[x] >= kMinLevel)) continue;
      const double ratio = g[x] / r[x];
      if (!(std::abs(ratio - 1.0) <= kEdge)) continue;  // edges, and NaN
      sums[b[x]] += ratio;
      counts[b[x]] += 1.0;
    }
  }
  MeasuredGain result;
  for (int k = 0; k < kBins * kBins; ++k)
    if (counts[k] >= kMinSamples) result.measured.push_back(k);
  if (result.measured.empty()) return std::nullopt;
  // Unmeasured bins take no part (weight 0) in the normalised convolution.
  for (int k = 0; k < kBins * kBins; ++k)
    if (counts[k] < kMinSamples) sums[k] = counts[k] = 0.0;
  const cv::Mat smoothed_sum = SmoothPeriodic(sum), smoothed_count = SmoothPeriodic(count);
  result.gain = cv::Mat(kBins, kBins, CV_64F);
  double weighted = 0.0, pixels = 0.0;
  for (int k = 0; k < kBins * kBins; ++k) {
    const double c = smoothed_count.ptr<double>()[k];
    const double value = c > 1e-9 ? smoothed_sum.ptr<double>()[k] / c : 1.0;
    result.gain.ptr<double>()[k] = value;
    weighted += value * counts[k];
    pixels += counts[k];
  }
  result.gain *= pixels / weighted;
  return result;
}

}  // namespace

LatticeGainReport FlattenLatticeGain(LightField& light_field, const HexLattice& lattice) {
  const LightFieldShape& shape = light_field.shape();
  LatticeGainReport report;
  if (!light_field.HasWeights() || shape.channels != 3 || shape.width < 32 || shape.height < 32) return report;
  const std::vector<std::uint8_t> bins = LensBins(lattice, shape.width, shape.height);
  FlattenEachLitView(
      light_field, kMinMeanWeight,
      [&](ViewIndex view, const cv::Mat& weight) -> std::optional<ViewGainDeviation> {
        cv::Mat rgb(shape.height, shape.width, CV_32FC3, light_field.ViewData(view));
        cv::Mat grey;
        cv::transform(rgb, grey, cv::Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
        const std::optional<MeasuredGain> measured = MeasureGain(grey, weight, bins);
        if (!measured) return std::nullopt;
        ViewGainDeviation deviation;
        double squares = 0.0;
        for (const int b : measured->measured) {
          const double g = measured->gain.ptr<double>()[b] - 1.0;
          squares += g * g;
          deviation.largest = std::max(deviation.largest, std::abs(g));
        }
        deviation.rms = std::sqrt(squares / static_cast<double>(measured->measured.size()));
        std::array<float, kBins * kBins> inverse{};
        for (int b = 0; b < kBins * kBins; ++b)
          inverse[static_cast<std::size_t>(b)] = static_cast<float>(1.0 / measured->gain.ptr<double>()[b]);
        for (int y = 0; y < shape.height; ++y) {
          auto* row = rgb.ptr<cv::Vec3f>(y);
          const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(shape.width);
          for (int x = 0; x < shape.width; ++x) row[x] *= inverse[b[x]];
        }
        return deviation;
      },
      report);
  return report;
}

}  // namespace lfsp::decode
