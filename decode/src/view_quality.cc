#include "lfsp/decode/view_quality.h"

#include <algorithm>
#include <cmath>
#include <complex>

#include "lfsp/core/channel_gains.h"
#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

constexpr double kBandShortest = 11.0, kBandLongest = 16.0;  // rows
constexpr double kReferenceShortest = 6.0, kReferenceLongest = 40.0;

// Row means of `quantity(r, g, b)` over the view.
template <typename Quantity>
std::vector<double> RowMeans(const LightField& light_field, ViewIndex view, Quantity quantity) {
  const LightFieldShape& shape = light_field.shape();
  if (shape.channels != 3) throw Error("band measure: the light field must be RGB");
  if (!shape.Contains(view)) throw Error("band measure: view outside the light field");
  std::vector<double> means(static_cast<std::size_t>(shape.height), 0.0);
  for (int y = 0; y < shape.height; ++y) {
    double sum = 0.0;
    for (int x = 0; x < shape.width; ++x)
      sum += quantity(light_field.at(view, y, x, 0), light_field.at(view, y, x, 1), light_field.at(view, y, x, 2));
    means[static_cast<std::size_t>(y)] = sum / shape.width;
  }
  return means;
}

}  // namespace

double RowBandRatio(const std::vector<double>& row_means) {
  const auto n = static_cast<int>(row_means.size());
  if (n < 48) return 0.0;
  double mean = 0.0;
  for (double m : row_means) mean += m;
  mean /= n;
  std::vector<double> windowed(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)  // numpy's np.hanning: 0 at both ends
    windowed[static_cast<std::size_t>(i)] =
        (row_means[static_cast<std::size_t>(i)] - mean) * (0.5 - 0.5 * std::cos(2.0 * M_PI * i / (n - 1)));
  double band = 0.0;
  std::vector<double> reference;
  for (int k = 1; k <= n / 2; ++k) {
    const double period = static_cast<double>(n) / k;
    if (period < kReferenceShortest || period > kReferenceLongest) continue;
    std::complex<double> sum = 0.0;
    for (int i = 0; i < n; ++i) sum += windowed[static_cast<std::size_t>(i)] * std::polar(1.0, -2.0 * M_PI * k * i / n);
    const double amplitude = std::abs(sum);
    reference.push_back(amplitude);
    if (period >= kBandShortest && period <= kBandLongest) band = std::max(band, amplitude);
  }
  if (reference.empty()) return 0.0;
  std::sort(reference.begin(), reference.end());
  const std::size_t half = reference.size() / 2;
  const double median = reference.size() % 2 ? reference[half] : 0.5 * (reference[half - 1] + reference[half]);
  return median > 0.0 ? band / median : 0.0;
}

double ChromaBandRatio(const LightField& light_field, ViewIndex view) {
  return RowBandRatio(RowMeans(light_field, view, [](float r, float g, float b) { return g - 0.5 * (r + b); }));
}

double LumaBandRatio(const LightField& light_field, ViewIndex view) {
  return RowBandRatio(RowMeans(light_field, view, [](float r, float g, float b) { return (r + g + b) / 3.0; }));
}

CentreFidelity CompareCentreWithTruth(const LightField& decoded, const LightField& truth, int border) {
  const LightFieldShape& a = decoded.shape();
  const LightFieldShape& b = truth.shape();
  if (a.width != b.width || a.height != b.height || a.channels != 3 || b.channels != 3 || a.width <= 2 * border ||
      a.height <= 2 * border)
    throw Error("centre fidelity: decode and truth differ in view size or are not RGB");
  const cv::Rect inside(border, border, a.width - 2 * border, a.height - 2 * border);
  const cv::Mat decoded_view = decoded.View(a.Centre())(inside), truth_view = truth.View(b.Centre())(inside);
  CentreFidelity fidelity;
  fidelity.gains = FitChannelGains(decoded_view, decoded.transfer, truth_view, truth.transfer);
  const auto linear = [](const LightField& field, int y, int x, int c) {
    return LinearSample(field.at(field.shape().Centre(), y, x, c), field.transfer);
  };
  double squared = 0.0, chroma = 0.0;
  long long pixels = 0;
  for (int y = border; y < a.height - border; ++y)
    for (int x = border; x < a.width - border; ++x) {
      double error[3];
      for (int c = 0; c < 3; ++c) {
        error[c] = fidelity.gains[static_cast<std::size_t>(c)] * linear(decoded, y, x, c) - linear(truth, y, x, c);
        squared += error[c] * error[c];
      }
      chroma += std::abs(error[1] - 0.5 * (error[0] + error[2]));
      ++pixels;
    }
  fidelity.psnr_db = 10.0 * std::log10(1.0 / std::max(squared / (3.0 * static_cast<double>(pixels)), 1e-12));
  fidelity.chroma_error = chroma / static_cast<double>(pixels);
  return fidelity;
}

}  // namespace lfsp::decode
