#include "lfsp/depth/lattice_peak.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>

namespace lfsp::depth {
namespace {

constexpr int kBlock = 64;  // Welch block side: bins of 1/64 cycle per pixel
// The map's frame left out, as the HCI metrics leave it out: there every stage's edge handling shows, not a lattice.
// On the real F01 frame IMG_2 the decoder's first columns, where the slicing's cubic folds its taps onto the first
// lens of the row, alternate row by row in disparity (0.34 / -0.23 px), and read 2.27 at (0, 1/2) with blocks
// from the map's corner; 1.45 with the 12 columns on each side cut off.
constexpr int kFrame = 15;
constexpr int kLocalWindow = 7;      // bins of the local median, per axis
constexpr double kLowestBins = 2.5;  // frequencies this near zero are the scene's falloff, not a pattern
constexpr double kHalfSqrt3 = 0.86602540378443864676;

// Wraps a frequency into [-0.5, 0.5).
double Wrapped(double f) { return f - std::floor(f + 0.5); }

// Welch's power spectrum: the mean over blocks of |DFT(hann * (block - its mean))|^2, index (v, u) at frequency
// (u / kBlock, v / kBlock) modulo 1.
cv::Mat WelchSpectrum(const cv::Mat& map) {
  cv::Mat filled;
  map.convertTo(filled, CV_64F);
  double sum = 0.0;
  long count = 0;
  for (int y = 0; y < filled.rows; ++y)
    for (int x = 0; x < filled.cols; ++x)
      if (const double value = filled.at<double>(y, x); std::isfinite(value)) {
        sum += value;
        ++count;
      }
  const double mean = count > 0 ? sum / static_cast<double>(count) : 0.0;
  for (int y = 0; y < filled.rows; ++y)
    for (int x = 0; x < filled.cols; ++x)
      if (!std::isfinite(filled.at<double>(y, x))) filled.at<double>(y, x) = mean;
  std::array<double, kBlock> hann{};
  for (int k = 0; k < kBlock; ++k) hann[k] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * k / (kBlock - 1));
  cv::Mat power = cv::Mat::zeros(kBlock, kBlock, CV_64F);
  int blocks = 0;
  cv::Mat windowed(kBlock, kBlock, CV_64F), spectrum;
  // Blocks overlapping by half, centred inside the frame.
  const auto first = [](int size) {
    const int inside = size - 2 * kFrame, steps = (inside - kBlock) / (kBlock / 2);
    return kFrame + (inside - kBlock - steps * (kBlock / 2)) / 2;
  };
  for (int y0 = first(filled.rows); y0 + kBlock <= filled.rows - kFrame; y0 += kBlock / 2)
    for (int x0 = first(filled.cols); x0 + kBlock <= filled.cols - kFrame; x0 += kBlock / 2) {
      const cv::Mat block = filled(cv::Rect(x0, y0, kBlock, kBlock));
      const double block_mean = cv::mean(block)[0];
      for (int y = 0; y < kBlock; ++y)
        for (int x = 0; x < kBlock; ++x)
          windowed.at<double>(y, x) = (block.at<double>(y, x) - block_mean) * hann[y] * hann[x];
      cv::dft(windowed, spectrum, cv::DFT_COMPLEX_OUTPUT);
      for (int v = 0; v < kBlock; ++v)
        for (int u = 0; u < kBlock; ++u) {
          const cv::Vec2d c = spectrum.at<cv::Vec2d>(v, u);
          power.at<double>(v, u) += c[0] * c[0] + c[1] * c[1];
        }
      ++blocks;
    }
  if (blocks > 0) power /= blocks;
  return power;
}

double Median(std::vector<double> values) {
  const std::size_t n = values.size();
  std::sort(values.begin(), values.end());
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

int Bin(long index) { return static_cast<int>(((index % kBlock) + kBlock) % kBlock); }

// Bin (u, v)'s power over the larger of its local median and its radial median (see the header).
double PeakRatio(const cv::Mat& power, int u, int v) {
  std::vector<double> local;
  local.reserve(kLocalWindow * kLocalWindow);
  for (int dv = -kLocalWindow / 2; dv <= kLocalWindow / 2; ++dv)
    for (int du = -kLocalWindow / 2; du <= kLocalWindow / 2; ++du)
      local.push_back(power.at<double>(Bin(v + dv), Bin(u + du)));
  const double fx = u < kBlock / 2 ? u : u - kBlock, fy = v < kBlock / 2 ? v : v - kBlock;  // in bins
  const double radius = std::hypot(fx, fy);
  std::vector<double> radial;
  for (const int step : {-4, -3, -2, 2, 3, 4}) {
    const double scale = 1.0 + step / radius;
    radial.push_back(power.at<double>(Bin(std::lround(fy * scale)), Bin(std::lround(fx * scale))));
  }
  const double reference = std::max(Median(local), Median(radial));
  return reference > 0.0 ? power.at<double>(v, u) / reference : 0.0;
}

}  // namespace

std::vector<MapFrequency> LensLatticeFrequencies(double spacing_x, double spacing_y, double rotation) {
  // Lens (i, j) sits at origin + (i + s_j / 2) a + j b (s_j: 1 on shifted rows), and view pixel x of row j samples
  // the row at i = x sqrt(3)/2 - s_j / 2. A sensor pattern exp(2 pi i k.p) then reads alpha = k.a cycles per lens
  // along a row and beta = k.b per row. Sampled at integer i, alpha aliases to alpha - round(alpha), which the
  // interpolation along the row carries to the view's x at sqrt(3)/2 of that; and the half-pitch shift of every
  // other row adds round(alpha) half cycles there, which alternates row by row when round(alpha) is odd.
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double ax = spacing_x * c, ay = spacing_x * s;   // a: along a row
  const double bx = -spacing_y * s, by = spacing_y * c;  // b: to the next row
  constexpr double kPeriod = 8.0;
  std::vector<MapFrequency> frequencies;
  for (int m = -4; m <= 4; ++m)
    for (int n = -4; n <= 4; ++n) {
      if (m == 0 && n == 0) continue;
      const double kx = m / kPeriod, ky = n / kPeriod;
      const double alpha = kx * ax + ky * ay, beta = kx * bx + ky * by;
      const double whole = std::round(alpha);
      frequencies.push_back({Wrapped(kHalfSqrt3 * (alpha - whole)), Wrapped(beta + 0.5 * whole)});
    }
  const double interpolation = 1.0 - kHalfSqrt3;
  frequencies.push_back({0.0, -0.5});
  frequencies.push_back({interpolation, -0.5});
  frequencies.push_back({2.0 * interpolation, 0.0});
  return frequencies;
}

std::optional<std::vector<MapFrequency>> LensLatticeFrequencies(const LightField& light_field) {
  const nlohmann::json& metadata = light_field.metadata;
  if (!metadata.contains("decode") || !metadata["decode"].is_object()) return std::nullopt;
  const nlohmann::json& decode = metadata["decode"];
  for (const char* key : {"grid_spacing_x", "grid_spacing_y", "grid_rotation"})
    if (!decode.contains(key) || !decode[key].is_number()) return std::nullopt;
  const double spacing_x = decode["grid_spacing_x"].get<double>(), spacing_y = decode["grid_spacing_y"].get<double>();
  const double rotation = decode["grid_rotation"].get<double>();
  if (!(spacing_x > 0.0 && spacing_y > 0.0 && std::isfinite(rotation))) return std::nullopt;
  return LensLatticeFrequencies(spacing_x, spacing_y, rotation);
}

std::optional<LatticePeak> StrongestLatticePeak(const cv::Mat& map, const std::vector<MapFrequency>& frequencies) {
  if (map.channels() != 1 || map.rows < 2 * (kBlock + kFrame) || map.cols < 2 * (kBlock + kFrame)) return std::nullopt;
  LatticePeak peak;
  const cv::Mat power = WelchSpectrum(map);
  for (const MapFrequency& f : frequencies) {
    if (std::hypot(f.fx, f.fy) * kBlock < kLowestBins) continue;
    // The bins on either side of the frequency, per axis (a pattern between bins shares its power between them), or
    // the one bin it falls on.
    const auto u0 = static_cast<long>(std::floor(f.fx * kBlock)), u1 = static_cast<long>(std::ceil(f.fx * kBlock));
    const auto v0 = static_cast<long>(std::floor(f.fy * kBlock)), v1 = static_cast<long>(std::ceil(f.fy * kBlock));
    for (long v = v0; v <= v1; ++v)
      for (long u = u0; u <= u1; ++u) {
        const double ratio = PeakRatio(power, Bin(u), Bin(v));
        if (ratio > peak.ratio) {
          peak.ratio = ratio;
          peak.frequency = f;
        }
      }
  }
  // A real map's spectrum is symmetric: report the frequency with fy >= 0.
  if (peak.frequency.fy < 0.0 || (peak.frequency.fy == 0.0 && peak.frequency.fx < 0.0))
    peak.frequency = {-peak.frequency.fx, -peak.frequency.fy};
  return peak;
}

nlohmann::ordered_json ToJson(const LatticePeak& peak) {
  return {{"ratio", peak.ratio}, {"fx", peak.frequency.fx}, {"fy", peak.frequency.fy}};
}

}  // namespace lfsp::depth
