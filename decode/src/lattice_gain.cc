#include "lfsp/decode/lattice_gain.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace lfsp::decode {
namespace {

constexpr int kBins = 16;  // per axis of the 2 x 2 px Bayer tile
// A view is compared with its own blur across lens rows only (Gaussian sigma, rows). Neighbouring lens rows fall on
// different parts of the Bayer tile, so the gain alternates from row to row while the scene's texture along a row
// cancels. A blur along rows as well (4 px) let texture whose period is near the bins' along a row (~15 px on an
// F01) leak in: 0.19 % of gain measured, and put in, on a clean synthetic plane, against 0.03 % now.
constexpr double kReferenceSigmaRows = 2.0;
constexpr double kEdge = 0.1;            // pixels differing from the blur by more than this share are edges: skipped
constexpr int kMinSamples = 20;          // per bin
constexpr double kBinSmoothing = 0.7;    // Gaussian sigma over the (periodic) bins
constexpr float kMinWeight = 0.02f;      // rays with less weight carry no usable light
constexpr double kMinMeanWeight = 0.05;  // views darker than this on average are left alone
constexpr double kMinLevel = 0.01;       // blurred linear level below which the ratio is noise

// For every decoded pixel, the bin of the sensor position of the lens it is sampled from (kBins^2 = 256 fit a byte).
static_assert(kBins * kBins <= 256);
std::vector<std::uint8_t> LensBins(const HexLattice& lattice, int width, int height) {
  std::vector<std::uint8_t> bins(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const double half_sqrt3 = 0.5 * std::sqrt(3.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double shift = 0.5 * lattice.Shift(y);
      const double along = std::nearbyint(x * half_sqrt3 - shift) + shift;
      double sx = 0.0, sy = 0.0;
      lattice.SensorPosition(along, y, 0.0, 0.0, sx, sy);
      const auto bin = [](double position) {
        const double phase = position - 2.0 * std::floor(0.5 * position);  // in [0, 2)
        return std::clamp(static_cast<int>(phase * 0.5 * kBins), 0, kBins - 1);
      };
      bins[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
          static_cast<std::uint8_t>(bin(sy) * kBins + bin(sx));
    }
  return bins;
}

// The bins' gains measured in one view (1 where too few pixels), smoothed over the periodic bins, mean 1.
cv::Mat MeasureGain(const cv::Mat& grey, const cv::Mat& weight, const std::vector<std::uint8_t>& bins) {
  cv::Mat reference;
  const int taps = 2 * static_cast<int>(std::ceil(3.0 * kReferenceSigmaRows)) + 1;
  cv::GaussianBlur(grey, reference, cv::Size(1, taps), 0.0, kReferenceSigmaRows, cv::BORDER_REFLECT);
  std::vector<double> sum(kBins * kBins, 0.0);
  std::vector<int> count(kBins * kBins, 0);
  const int margin = static_cast<int>(2 * kReferenceSigmaRows);
  for (int y = margin; y < grey.rows - margin; ++y) {
    const float* g = grey.ptr<float>(y);
    const float* r = reference.ptr<float>(y);
    const float* w = weight.ptr<float>(y);
    const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(grey.cols);
    for (int x = margin; x < grey.cols - margin; ++x) {
      if (w[x] < kMinWeight || r[x] < kMinLevel) continue;
      const double ratio = g[x] / r[x];
      if (std::abs(ratio - 1.0) > kEdge) continue;
      sum[static_cast<std::size_t>(b[x])] += ratio;
      ++count[static_cast<std::size_t>(b[x])];
    }
  }
  cv::Mat gain(kBins, kBins, CV_64F);
  long samples = 0;
  for (int k = 0; k < kBins * kBins; ++k) {
    const auto n = static_cast<std::size_t>(k);
    const bool measured = count[n] >= kMinSamples;
    gain.at<double>(k / kBins, k % kBins) = measured ? sum[n] / count[n] : 1.0;
    samples += count[n];
  }
  // Smooth across the periodic bins (wrap the border), then normalise so that the view keeps its brightness.
  cv::Mat padded, smoothed;
  const int pad = 3;
  cv::copyMakeBorder(gain, padded, pad, pad, pad, pad, cv::BORDER_WRAP);
  cv::GaussianBlur(padded, smoothed, cv::Size(2 * pad + 1, 2 * pad + 1), kBinSmoothing, 0.0, cv::BORDER_REPLICATE);
  gain = smoothed(cv::Rect(pad, pad, kBins, kBins)).clone();
  if (samples > 0) gain *= 1.0 / cv::mean(gain)[0];
  return gain;
}

}  // namespace

LatticeGainReport FlattenLatticeGain(LightField& light_field, const HexLattice& lattice) {
  const LightFieldShape& shape = light_field.shape();
  LatticeGainReport report;
  if (!light_field.HasWeights() || shape.width < 32 || shape.height < 32) return report;
  const std::vector<std::uint8_t> bins = LensBins(lattice, shape.width, shape.height);
  const int views = shape.nu * shape.nv;
  std::vector<double> rms(static_cast<std::size_t>(views), -1.0), largest(static_cast<std::size_t>(views), 0.0);
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < views; ++k) {
    const ViewIndex view{k % shape.nu, k / shape.nu};
    const cv::Mat weight(shape.height, shape.width, CV_32F, light_field.weights().ViewData(view));
    if (cv::mean(weight)[0] < kMinMeanWeight) continue;
    cv::Mat rgb(shape.height, shape.width, CV_32FC3, light_field.ViewData(view));
    cv::Mat grey;
    cv::transform(rgb, grey, cv::Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
    const cv::Mat gain = MeasureGain(grey, weight, bins);
    double squares = 0.0, worst = 0.0;
    std::array<float, kBins * kBins> inverse{};
    for (int b = 0; b < kBins * kBins; ++b) {
      const double value = gain.at<double>(b / kBins, b % kBins);
      squares += (value - 1.0) * (value - 1.0);
      worst = std::max(worst, std::abs(value - 1.0));
      inverse[static_cast<std::size_t>(b)] = static_cast<float>(1.0 / value);
    }
    rms[static_cast<std::size_t>(k)] = std::sqrt(squares / (kBins * kBins));
    largest[static_cast<std::size_t>(k)] = worst;
    for (int y = 0; y < shape.height; ++y) {
      auto* row = rgb.ptr<cv::Vec3f>(y);
      const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(shape.width);
      for (int x = 0; x < shape.width; ++x) row[x] *= inverse[b[x]];
    }
  }
  for (int k = 0; k < views; ++k) {
    if (rms[static_cast<std::size_t>(k)] < 0.0) continue;
    report.rms += rms[static_cast<std::size_t>(k)];
    report.max = std::max(report.max, largest[static_cast<std::size_t>(k)]);
    ++report.views;
  }
  if (report.views > 0) report.rms /= report.views;
  return report;
}

}  // namespace lfsp::decode
