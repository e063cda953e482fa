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

namespace lfsp::decode {
namespace {

constexpr int kBins = 32;  // over the block's height
// Brightness classes (quarters of the view's lit pixels by local mean), each with its own gain: the quantization
// error is a matter of codes, so its share of a sample depends on how bright the sample is. On the simulated dark
// F01 JPEG capture one class for all took the error at the blocks' beat in colour from 46.0 to 37.6 (x1e-4), four
// to 35.7, and the whole error from 503 to 501 and 487; on IMG_3 the per-pixel disparity's peak at the beat read 4.7
// with one class, 3.0 with four.
constexpr int kClasses = 4;
constexpr int kCells = kClasses * kBins;
constexpr int kRounds = 3;                      // each measures what the last one left
constexpr double kReferenceSigmaRows = 6.0;     // the local mean: wider than half the 13-14 row cycle...
constexpr double kReferenceSigmaColumns = 2.0;  // ...and narrow along the row, where the scene changes fastest
constexpr double kEdge = 0.2;                   // pixels differing from the local mean by more than this share: skipped
constexpr double kBinSmoothing = 1.0;           // Gaussian sigma over the (periodic) bins
constexpr float kMinWeight = 0.05f;             // rays with less weight carry no usable light
constexpr double kMinMeanWeight = 0.05;         // views darker than this on average are left alone
constexpr double kMinLevel = 0.005;             // local mean below which the ratio is noise
constexpr int kMinSamples = 20;                 // a view whose every bin has fewer is left alone

// Sensor row of the lens nearest to where each decoded pixel is sampled (as LensBins in lattice_gain.cc: the
// slicing's cubic mixes up to four lenses of the row, the nearest weighs most).
std::vector<float> LensRows(const HexLattice& lattice, int width, int height) {
  std::vector<float> rows(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const double pitches_per_column = 0.5 * std::numbers::sqrt3;  // DecodedGeometry: x * sqrt(3)/2 along the row
  for (int y = 0; y < height; ++y) {
    const double shift = 0.5 * lattice.Shift(y);
    for (int x = 0; x < width; ++x) {
      double sx = 0.0, sy = 0.0;
      lattice.SensorPosition(std::nearbyint(x * pitches_per_column - shift) + shift, y, 0.0, 0.0, sx, sy);
      rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
          static_cast<float>(sy);
    }
  }
  return rows;
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

using ChannelGains = std::array<std::array<double, kCells>, 3>;

// The local mean of each lit pixel's channels (the view's lit pixels blurred, over the blurred coverage); 0 where
// nothing lit is near.
cv::Mat LocalMean(const cv::Mat& rgb, const cv::Mat& lit, const cv::Mat& coverage) {
  cv::Mat masked = cv::Mat::zeros(rgb.size(), rgb.type()), blurred;
  rgb.copyTo(masked, lit);
  cv::GaussianBlur(masked, blurred, cv::Size(), kReferenceSigmaColumns, kReferenceSigmaRows, cv::BORDER_REFLECT);
  for (int y = 0; y < rgb.rows; ++y) {
    auto* m = blurred.ptr<cv::Vec3f>(y);
    const float* c = coverage.ptr<float>(y);
    for (int x = 0; x < rgb.cols; ++x) m[x] = c[x] > 1e-3f ? m[x] / c[x] : cv::Vec3f(0.0f, 0.0f, 0.0f);
  }
  return blurred;
}

// Each pixel's brightness class per channel (CV_8UC3): which quarter of the lit pixels' local means it falls in.
cv::Mat BrightnessClasses(const cv::Mat& local, const cv::Mat& lit) {
  std::array<std::vector<float>, 3> levels;
  for (int y = 0; y < local.rows; ++y) {
    const auto* m = local.ptr<cv::Vec3f>(y);
    const std::uint8_t* l = lit.ptr<std::uint8_t>(y);
    for (int x = 0; x < local.cols; ++x)
      if (l[x])
        for (int ch = 0; ch < 3; ++ch) levels[static_cast<std::size_t>(ch)].push_back(m[x][ch]);
  }
  std::array<std::array<float, kClasses - 1>, 3> bounds{};
  for (std::size_t ch = 0; ch < 3; ++ch) {
    std::vector<float>& values = levels[ch];
    if (values.empty()) continue;
    for (int q = 1; q < kClasses; ++q) {
      const auto at = values.begin() + static_cast<std::ptrdiff_t>(values.size() * q / kClasses);
      std::nth_element(values.begin(), at, values.end());
      bounds[ch][static_cast<std::size_t>(q - 1)] = *at;
    }
  }
  cv::Mat classes(local.size(), CV_8UC3);
  for (int y = 0; y < local.rows; ++y) {
    const auto* m = local.ptr<cv::Vec3f>(y);
    auto* out = classes.ptr<cv::Vec3b>(y);
    for (int x = 0; x < local.cols; ++x)
      for (int ch = 0; ch < 3; ++ch) {
        const auto& b = bounds[static_cast<std::size_t>(ch)];
        out[x][ch] = static_cast<std::uint8_t>(std::upper_bound(b.begin(), b.end(), m[x][ch]) - b.begin());
      }
  }
  return classes;
}

// The gain of each channel by brightness class and bin: the mean ratio of the lit pixels to their local mean,
// smoothed over the bins of each class as a normalised convolution, normalised so that the lit pixels keep their
// mean. A channel whose every cell has too few samples keeps gain 1; false when none was measured.
bool MeasureGains(const cv::Mat& rgb, const cv::Mat& lit, const cv::Mat& local, const cv::Mat& classes,
                  const std::vector<std::uint8_t>& bins, ChannelGains& gains) {
  std::array<std::array<double, kCells>, 3> sums{}, counts{}, lit_pixels{};
  const int margin = static_cast<int>(std::ceil(kReferenceSigmaRows));  // rows the blur reflects into
  for (int y = 0; y < rgb.rows; ++y) {
    const auto* value = rgb.ptr<cv::Vec3f>(y);
    const auto* m = local.ptr<cv::Vec3f>(y);
    const auto* k = classes.ptr<cv::Vec3b>(y);
    const std::uint8_t* l = lit.ptr<std::uint8_t>(y);
    const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(rgb.cols);
    const bool inside = y >= margin && y < rgb.rows - margin;
    for (int x = 0; x < rgb.cols; ++x) {
      if (!l[x]) continue;
      for (int ch = 0; ch < 3; ++ch) {
        const auto cell = static_cast<std::size_t>(k[x][ch] * kBins + b[x]);
        lit_pixels[static_cast<std::size_t>(ch)][cell] += 1.0;
        const double level = m[x][ch];
        if (!inside || !(level >= kMinLevel)) continue;
        const double ratio = value[x][ch] / level;
        if (!(std::abs(ratio - 1.0) <= kEdge)) continue;  // edges, and NaN
        sums[static_cast<std::size_t>(ch)][cell] += ratio;
        counts[static_cast<std::size_t>(ch)][cell] += 1.0;
      }
    }
  }
  bool measured = false;
  for (std::size_t ch = 0; ch < 3; ++ch) {
    std::array<double, kCells>& gain = gains[ch];
    gain.fill(1.0);
    if (*std::max_element(counts[ch].begin(), counts[ch].end()) < kMinSamples) continue;
    for (std::size_t first = 0; first < kCells; first += kBins) {
      std::array<double, kBins> class_sums{}, class_counts{};
      std::copy_n(sums[ch].begin() + static_cast<std::ptrdiff_t>(first), kBins, class_sums.begin());
      std::copy_n(counts[ch].begin() + static_cast<std::ptrdiff_t>(first), kBins, class_counts.begin());
      const std::array<double, kBins> smoothed_sums = SmoothPeriodic(class_sums);
      const std::array<double, kBins> smoothed_counts = SmoothPeriodic(class_counts);
      for (std::size_t k = 0; k < kBins; ++k)
        gain[first + k] = smoothed_counts[k] > 1e-9 ? smoothed_sums[k] / smoothed_counts[k] : 1.0;
    }
    // Normalised over every lit pixel (not only those measured), so the view keeps its brightness.
    double weighted = 0.0, pixels = 0.0;
    for (std::size_t cell = 0; cell < kCells; ++cell) {
      weighted += gain[cell] * lit_pixels[ch][cell];
      pixels += lit_pixels[ch][cell];
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
  const double c = std::cos(lattice.rotation), s = std::sin(lattice.rotation);
  const int centre_u = (shape.nu - 1) / 2, centre_v = (shape.nv - 1) / 2;
  const int views = shape.nu * shape.nv;
  std::vector<double> rms(static_cast<std::size_t>(views), -1.0), largest(static_cast<std::size_t>(views), 0.0);
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < views; ++k) {
    const ViewIndex view{k % shape.nu, k / shape.nu};
    const cv::Mat weight(shape.height, shape.width, CV_32F, light_field.weights().ViewData(view));
    if (cv::mean(weight)[0] < kMinMeanWeight) continue;
    const cv::Mat lit = weight >= kMinWeight;
    // Where this view's samples fall down the block: the lens centre's sensor row plus the view's offset (as the
    // slicing places them).
    const double along = (view.u - centre_u) * view_step, across = (view.v - centre_v) * view_step;
    const double offset = s * along + c * across;
    std::vector<std::uint8_t> bins(lens_rows.size());
    for (std::size_t i = 0; i < bins.size(); ++i) {
      const double row = lens_rows[i] + offset;
      const double phase = (row - block * std::floor(row / block)) / block;  // in [0, 1)
      bins[i] = static_cast<std::uint8_t>(std::clamp(static_cast<int>(phase * kBins), 0, kBins - 1));
    }
    cv::Mat rgb(shape.height, shape.width, CV_32FC3, light_field.ViewData(view));
    cv::Mat lit_float, coverage;
    lit.convertTo(lit_float, CV_32F, 1.0 / 255.0);
    cv::GaussianBlur(lit_float, coverage, cv::Size(), kReferenceSigmaColumns, kReferenceSigmaRows, cv::BORDER_REFLECT);
    // What each sample has been divided by, over the rounds (for the report).
    cv::Mat divided(rgb.size(), CV_32FC3, cv::Scalar::all(1.0));
    bool measured = false;
    for (int round = 0; round < kRounds; ++round) {
      const cv::Mat local = LocalMean(rgb, lit, coverage);
      const cv::Mat classes = BrightnessClasses(local, lit);
      ChannelGains gains;
      if (!MeasureGains(rgb, lit, local, classes, bins, gains)) break;
      measured = true;
      for (int y = 0; y < shape.height; ++y) {
        auto* row = rgb.ptr<cv::Vec3f>(y);
        auto* total = divided.ptr<cv::Vec3f>(y);
        const auto* k = classes.ptr<cv::Vec3b>(y);
        const std::uint8_t* b = bins.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(shape.width);
        for (int x = 0; x < shape.width; ++x)
          for (int ch = 0; ch < 3; ++ch) {
            const auto gain = static_cast<float>(
                gains[static_cast<std::size_t>(ch)][static_cast<std::size_t>(k[x][ch] * kBins + b[x])]);
            row[x][ch] /= gain;
            total[x][ch] *= gain;
          }
      }
    }
    if (!measured) continue;
    double squares = 0.0, worst = 0.0;
    long count = 0;
    for (int y = 0; y < shape.height; ++y) {
      const auto* total = divided.ptr<cv::Vec3f>(y);
      const std::uint8_t* l = lit.ptr<std::uint8_t>(y);
      for (int x = 0; x < shape.width; ++x)
        if (l[x])
          for (int ch = 0; ch < 3; ++ch) {
            const double deviation = total[x][ch] - 1.0;
            squares += deviation * deviation;
            worst = std::max(worst, std::abs(deviation));
            ++count;
          }
    }
    rms[static_cast<std::size_t>(k)] = count > 0 ? std::sqrt(squares / static_cast<double>(count)) : 0.0;
    largest[static_cast<std::size_t>(k)] = worst;
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
  const double along = (view.u - (shape.nu - 1) / 2) * view_step, across = (view.v - (shape.nv - 1) / 2) * view_step;
  const double offset = std::sin(lattice.rotation) * along + std::cos(lattice.rotation) * across;
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
