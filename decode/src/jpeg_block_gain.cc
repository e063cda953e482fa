#include "lfsp/decode/jpeg_block_gain.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfsp/core/srgb.h"
#include "view_gain_common.h"
namespace lfsp::decode {
namespace {

constexpr int kBins = 32;                       // over the block's height
constexpr int kRounds = 3;                      // each measures what the last one left
constexpr double kReferenceSigmaRows = 6.0;     // the local mean: wider than half the 13-14 row cycle...
constexpr double kReferenceSigmaColumns = 2.0;  // ...and narrow along the row, where the scene changes fastest
constexpr double kEdge = 0.2;                   // pixels differing from the local mean by more than this share: skipped
constexpr double kBinSmoothing = 1.0;           // Gaussian sigma over the (periodic) bins
constexpr float kMinWeight = 0.05f;             // rays with less weight carry no usable light
constexpr double kMinMeanWeight = 0.05;         // views darker than this on average are left alone
constexpr double kMinLevel = 0.005;             // local mean below which the ratio is noise
constexpr int kMinSamples = 20;                 // a view whose every bin has fewer is left alone

// Sensor row of the lens nearest to where each decoded pixel is sampled (ForEachNearestLens).
std::vector<float> LensRows(const HexLattice& lattice, int width, int height) {
  std::vector<float> rows(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  ForEachNearestLens(lattice, width, height, [&](int x, int y, double, double sy) {
    rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
        static_cast<float>(sy);
  });
  return rows;
}

// How far view `view`'s samples lie down the sensor from their lens centres (px): the view's offset from the centre
// view, as the slicing places them, along the lattice's column direction.
double ViewRowOffset(const HexLattice& lattice, const LightFieldShape& shape, ViewIndex view, double view_step) {
  const double along = (view.u - (shape.nu - 1) / 2) * view_step, across = (view.v - (shape.nv - 1) / 2) * view_step;
  return std::sin(lattice.rotation) * along + std::cos(lattice.rotation) * across;
}

// Smooths kBins values over their periodic index.
std::array<double, kBins> SmoothPeriodic(const std::array<double, kBins>& values) {
  std::array<double, 7> kernel{};
  double total = 0.0;
  for (int d = -3; d <= 3; ++d)
    total += kernel[static_cast<std::size_t>(d + 3)] = std::exp(-0.5 * d * d / (kBinSmoothing * kBinSmoothing));
  std::array<double, kBins> smoothed{};
  for (int k = 0; k < kBins; ++k)
    for (int d = -3; d <= 3; ++d)
      smoothed[static_cast<std::size_t>(k)] +=
          kernel[static_cast<std::size_t>(d + 3)] / total * values[static_cast<std::size_t>((k + d + kBins) % kBins)];
  return smoothed;
}

using ChannelGains = std::array<std::array<double, kBins>, 3>;

// The gain of each channel by bin: its mean ratio to the local mean (the view's lit pixels blurred, over the blurred
// coverage), smoothed over the bins as a normalised convolution, normalised so that the lit pixels keep their mean.
// A channel whose every bin has too few samples keeps gain 1; false when none was measured.
bool MeasureGains(const cv::Mat& rgb, const cv::Mat& lit, const cv::Mat& coverage,
                  const std::vector<std::uint8_t>& bins, ChannelGains& gains) {
  cv::Mat masked = cv::Mat::zeros(rgb.size(), rgb.type()), reference;
  rgb.copyTo(masked, lit);
  cv::GaussianBlur(masked, reference, cv::Size(), kReferenceSigmaColumns, kReferenceSigmaRows, cv::BORDER_REFLECT);
  std::array<std::array<double, kBins>, 3> sums{}, counts{};
  const int margin = static_cast<int>(std::ceil(kReferenceSigmaRows));  // rows the blur reflects into
  for (int y = margin; y < rgb.rows - margin; ++y) {
    const auto* value = rgb.ptr<cv::Vec3f>(y);
    const auto* r = reference.ptr<cv::Vec3f>(y);
    const float* c = coverage.ptr<float>(y);
    const std::uint8_t* l = lit.ptr<std::uint8_t>(y);
    const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(rgb.cols);
    for (int x = 0; x < rgb.cols; ++x) {
      if (!l[x] || !(c[x] > 1e-3f)) continue;
      for (int ch = 0; ch < 3; ++ch) {
        const double level = r[x][ch] / c[x];
        if (!(level >= kMinLevel)) continue;
        const double ratio = value[x][ch] / level;
        if (!(std::abs(ratio - 1.0) <= kEdge)) continue;  // edges, and NaN
        sums[static_cast<std::size_t>(ch)][b[x]] += ratio;
        counts[static_cast<std::size_t>(ch)][b[x]] += 1.0;
      }
    }
  }
  // Normalised over every lit pixel (not only those measured), so the view keeps its brightness.
  std::array<double, kBins> lit_pixels{};
  for (int y = 0; y < rgb.rows; ++y) {
    const std::uint8_t* l = lit.ptr<std::uint8_t>(y);
    const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(rgb.cols);
    for (int x = 0; x < rgb.cols; ++x)
      if (l[x]) lit_pixels[b[x]] += 1.0;
  }
  bool measured = false;
  for (std::size_t ch = 0; ch < 3; ++ch) {
    std::array<double, kBins>& gain = gains[ch];
    gain.fill(1.0);
    if (*std::max_element(counts[ch].begin(), counts[ch].end()) < kMinSamples) continue;
    const std::array<double, kBins> smoothed_sums = SmoothPeriodic(sums[ch]);
    const std::array<double, kBins> smoothed_counts = SmoothPeriodic(counts[ch]);
    double weighted = 0.0, pixels = 0.0;
    for (std::size_t k = 0; k < kBins; ++k) {
      gain[k] = smoothed_counts[k] > 1e-9 ? smoothed_sums[k] / smoothed_counts[k] : 1.0;
      weighted += gain[k] * lit_pixels[k];
      pixels += lit_pixels[k];
    }
    if (!(weighted > 0.0)) {
      gain.fill(1.0);
      continue;
    }
    for (double& g : gain) g *= pixels / weighted;
    measured = true;
  }
  return measured;
}

}  // namespace

JpegBlockGainReport FlattenJpegBlockGain(LightField& light_field, const HexLattice& lattice, double view_step,
                                         int block) {
  const LightFieldShape& shape = light_field.shape();
  JpegBlockGainReport report;
  if (!light_field.HasWeights() || shape.channels != 3 || shape.width < 32 || shape.height < 32 || block < 2)
    return report;
  const std::vector<float> lens_rows = LensRows(lattice, shape.width, shape.height);
  FlattenEachLitView(
      light_field, kMinMeanWeight,
      [&](ViewIndex view, const cv::Mat& weight) -> std::optional<ViewGainDeviation> {
        const cv::Mat lit = weight >= kMinWeight;
        // Where this view's samples fall down the block: the lens centre's sensor row plus the view's offset.
        const double offset = ViewRowOffset(lattice, shape, view, view_step);
        std::vector<std::uint8_t> bins(lens_rows.size());
        for (std::size_t i = 0; i < bins.size(); ++i) {
          const double row = lens_rows[i] + offset;
          const double phase = (row - block * std::floor(row / block)) / block;  // in [0, 1)
          bins[i] = static_cast<std::uint8_t>(std::clamp(static_cast<int>(phase * kBins), 0, kBins - 1));
        }
        cv::Mat rgb(shape.height, shape.width, CV_32FC3, light_field.ViewData(view));
        cv::Mat lit_float, coverage;
        lit.convertTo(lit_float, CV_32F, 1.0 / 255.0);
        cv::GaussianBlur(lit_float, coverage, cv::Size(), kReferenceSigmaColumns, kReferenceSigmaRows,
                         cv::BORDER_REFLECT);
        ChannelGains total;
        for (auto& channel_total : total) channel_total.fill(1.0);
        bool measured = false;
        for (int round = 0; round < kRounds; ++round) {
          ChannelGains gains;
          if (!MeasureGains(rgb, lit, coverage, bins, gains)) break;
          measured = true;
          std::array<cv::Vec3f, kBins> inverse{};
          for (std::size_t b = 0; b < kBins; ++b)
            for (std::size_t ch = 0; ch < 3; ++ch) {
              inverse[b][static_cast<int>(ch)] = static_cast<float>(1.0 / gains[ch][b]);
              total[ch][b] *= gains[ch][b];
            }
          for (int y = 0; y < shape.height; ++y) {
            auto* row = rgb.ptr<cv::Vec3f>(y);
            const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(shape.width);
            for (int x = 0; x < shape.width; ++x) row[x] = row[x].mul(inverse[b[x]]);
          }
        }
        if (!measured) return std::nullopt;
        ViewGainDeviation deviation;
        double squares = 0.0;
        for (const auto& channel_total : total)
          for (const double g : channel_total) {
            squares += (g - 1.0) * (g - 1.0);
            deviation.largest = std::max(deviation.largest, std::abs(g - 1.0));
          }
        deviation.rms = std::sqrt(squares / (3.0 * kBins));
        return deviation;
      },
      report);
  return report;
}

double BlockRowLuminance(const LightField& light_field, ViewIndex view, const HexLattice& lattice, double view_step,
                         int block) {
  const LightFieldShape& shape = light_field.shape();
  if (shape.channels != 3 || !shape.Contains(view) || block < 2) return 0.0;
  const bool srgb = light_field.transfer == Transfer::kSrgb;
  cv::Mat luma(shape.height, shape.width, CV_64F), local;
  for (int y = 0; y < shape.height; ++y)
    for (int x = 0; x < shape.width; ++x) {
      double sum = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double value = light_field.at(view, y, x, c);
        sum += srgb ? SrgbToLinear(value) : value;
      }
      luma.at<double>(y, x) = sum / 3.0;
    }
  cv::GaussianBlur(luma, local, cv::Size(), kReferenceSigmaColumns, kReferenceSigmaRows, cv::BORDER_REFLECT);
  const std::vector<float> lens_rows = LensRows(lattice, shape.width, shape.height);
  const double offset = ViewRowOffset(lattice, shape, view, view_step);
  std::complex<double> first = 0.0, second = 0.0;
  long count = 0;
  const int margin = static_cast<int>(std::ceil(kReferenceSigmaRows));
  for (int y = margin; y < shape.height - margin; ++y)
    for (int x = 0; x < shape.width; ++x) {
      const double level = local.at<double>(y, x);
      const double ratio = (luma.at<double>(y, x) - level) / level;
      if ((light_field.HasWeights() && light_field.weights().at(view, y, x) < kMinWeight) || !(level > kMinLevel) ||
          !(std::abs(ratio) < kEdge))
        continue;
      const double row =
          lens_rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(shape.width) + static_cast<std::size_t>(x)] +
          offset;
      const double phase = 2.0 * std::numbers::pi * row / block;
      first += ratio * std::polar(1.0, -phase);
      second += ratio * std::polar(1.0, -2.0 * phase);
      ++count;
    }
  if (count == 0) return 0.0;
  return 200.0 * std::hypot(std::abs(first), std::abs(second)) / static_cast<double>(count);
}

}  // namespace lfsp::decode
