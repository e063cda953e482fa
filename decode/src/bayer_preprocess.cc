#include "bayer_preprocess.h"

#include <omp.h>

#include <algorithm>
#include <vector>

#include "lfsp/core/error.h"

namespace lfsp::decode {

cv::Mat ApplyLevels(const RawImage& raw, const PhaseLevels& levels) {
  cv::Mat bayer(raw.height, raw.width, CV_32F);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < raw.height; ++y) {
    const std::uint16_t* in = raw.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(raw.width);
    float* out = bayer.ptr<float>(y);
    for (int x = 0; x < raw.width; ++x) {
      const auto phase = static_cast<std::size_t>(BayerPhase(x, y));
      out[x] = std::max(0.0f, (static_cast<float>(in[x]) - levels.black[phase]) * levels.scale[phase]);
    }
  }
  return bayer;
}

double Percentile999(const cv::Mat& image, float top) {
  constexpr int kBins = 8192;
  std::vector<long long> histogram(kBins, 0);
#pragma omp parallel
  {
    std::vector<long long> local(kBins, 0);
#pragma omp for schedule(static)
    for (int y = 0; y < image.rows; ++y) {
      const float* row = image.ptr<float>(y);
      for (int x = 0; x < image.cols; ++x)
        ++local[static_cast<std::size_t>(std::clamp(static_cast<int>(row[x] / top * kBins), 0, kBins - 1))];
    }
#pragma omp critical
    for (int b = 0; b < kBins; ++b) histogram[static_cast<std::size_t>(b)] += local[static_cast<std::size_t>(b)];
  }
  const auto wanted = static_cast<long long>(0.999 * static_cast<double>(image.total()));
  long long count = 0;
  int bin = 0;
  while (bin < kBins - 1 && count + histogram[static_cast<std::size_t>(bin)] < wanted)
    count += histogram[static_cast<std::size_t>(bin++)];
  return (bin + 1.0) * top / kBins;
}

cv::Mat InverseWhite(const RawImage& white, const PhaseLevels& white_levels, const std::array<float, 4>& white_gain,
                     float min_white, const std::string& source) {
  cv::Mat levelled = ApplyLevels(white, white_levels);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < levelled.rows; ++y) {
    float* row = levelled.ptr<float>(y);
    for (int x = 0; x < levelled.cols; ++x) row[x] *= white_gain[static_cast<std::size_t>(BayerPhase(x, y))];
  }
  const float top = 1.1f * *std::max_element(white_gain.begin(), white_gain.end());
  const double peak = Percentile999(levelled, top);
  if (!(peak > 0.0)) throw Error(source + ": white image is black");
  const auto inverse_peak = static_cast<float>(1.0 / peak);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < levelled.rows; ++y) {
    float* row = levelled.ptr<float>(y);
    for (int x = 0; x < levelled.cols; ++x) row[x] = 1.0f / std::max(min_white, row[x] * inverse_peak);
  }
  return levelled;
}

cv::Mat LevelAndDevignette(const RawImage& raw, const PhaseLevels& levels, const cv::Mat& inverse_white,
                           float hot_margin, long& hot_pixels, long& clipped_samples) {
  const int width = raw.width, height = raw.height;
  if (inverse_white.cols != width || inverse_white.rows != height)
    throw Error("white image and capture differ in size: they must come from the same sensor");
  cv::Mat bayer(height, width, CV_32F);
  long found = 0, clipped = 0;
  auto row_of = [&](int y) {
    return raw.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
  };
#pragma omp parallel for schedule(static) reduction(+ : found, clipped)
  for (int y = 0; y < height; ++y) {
    const std::uint16_t* row = row_of(y);
    const bool interior_row = hot_margin > 0.0f && y >= 2 && y < height - 2;
    const std::uint16_t* up = interior_row ? row_of(y - 2) : nullptr;
    const std::uint16_t* down = interior_row ? row_of(y + 2) : nullptr;
    const float* inverse = inverse_white.ptr<float>(y);
    float* out = bayer.ptr<float>(y);
    // Same-colour neighbours share the phase and so the levels: compare raw values, margin in raw units.
    const std::size_t row_phase = 2 * static_cast<std::size_t>(y & 1);
    const float margin[2] = {hot_margin / levels.scale[row_phase], hot_margin / levels.scale[row_phase + 1]};
    for (int x = 0; x < width; ++x) {
      const std::size_t phase = row_phase + static_cast<std::size_t>(x & 1);
      auto value = static_cast<float>(row[x]);
      if (interior_row && x >= 2 && x < width - 2) {
        const float limit = value - margin[x & 1];
        if (limit > row[x - 2] && limit > row[x + 2] && limit > up[x] && limit > down[x] && limit > up[x - 2] &&
            limit > up[x + 2] && limit > down[x - 2] && limit > down[x + 2]) {
          value = 0.25f * (static_cast<float>(row[x - 2]) + row[x + 2] + up[x] + down[x]);
          ++found;
        }
      }
      const float levelled = (value - levels.black[phase]) * levels.scale[phase];
      if (levelled >= kClippedLevel) ++clipped;
      out[x] = levelled * inverse[x];
    }
  }
  hot_pixels = found;
  clipped_samples = clipped;
  return bayer;
}

}  // namespace lfsp::decode
