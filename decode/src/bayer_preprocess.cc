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
    const std::size_t row_phase = 2 * static_cast<std::size_t>(y & 1);
    const float black0 = levels.black[row_phase], black1 = levels.black[row_phase + 1];
    const float scale0 = levels.scale[row_phase], scale1 = levels.scale[row_phase + 1];
    for (int x = 0; x + 1 < raw.width; x += 2) {
      out[x] = std::max(0.0f, (static_cast<float>(in[x]) - black0) * scale0);
      out[x + 1] = std::max(0.0f, (static_cast<float>(in[x + 1]) - black1) * scale1);
    }
    if (raw.width & 1) out[raw.width - 1] = std::max(0.0f, (static_cast<float>(in[raw.width - 1]) - black0) * scale0);
  }
  return bayer;
}

long CorrectHotPixels(cv::Mat& bayer, float margin) {
  struct Fix {
    int x;
    int y;
    float value;
  };
  const int width = bayer.cols, height = bayer.rows;
  std::vector<std::vector<Fix>> fixes(static_cast<std::size_t>(height));
#pragma omp parallel for schedule(static)
  for (int y = 2; y < height - 2; ++y) {
    const float* row = bayer.ptr<float>(y);
    const float* up = bayer.ptr<float>(y - 2);
    const float* down = bayer.ptr<float>(y + 2);
    for (int x = 2; x < width - 2; ++x) {
      const float value = row[x];
      // Cheap rejection first: most pixels are not above their left/right neighbours by the margin.
      if (value - margin <= row[x - 2] || value - margin <= row[x + 2]) continue;
      const float neighbours = std::max({up[x - 2], up[x], up[x + 2], down[x - 2], down[x], down[x + 2]});
      if (value - margin <= neighbours) continue;
      fixes[static_cast<std::size_t>(y)].push_back({x, y, 0.25f * (row[x - 2] + row[x + 2] + up[x] + down[x])});
    }
  }
  long count = 0;
  for (const auto& row : fixes)
    for (const Fix& fix : row) {
      bayer.at<float>(fix.y, fix.x) = fix.value;
      ++count;
    }
  return count;
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

void Devignette(cv::Mat& bayer, const RawImage& white, const PhaseLevels& white_levels,
                const std::array<float, 4>& white_gain, float min_white, const std::string& source) {
  if (white.width != bayer.cols || white.height != bayer.rows || white.pixels.size() != white.PixelCount())
    throw Error(source + ": white image is " + std::to_string(white.width) + "x" + std::to_string(white.height) +
                ", the capture " + std::to_string(bayer.cols) + "x" + std::to_string(bayer.rows) +
                ": they must come from the same sensor");
  // The levelled, gain-corrected white image, then its 99.9th percentile.
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
  for (int y = 0; y < bayer.rows; ++y) {
    float* row = bayer.ptr<float>(y);
    const float* w = levelled.ptr<float>(y);
    for (int x = 0; x < bayer.cols; ++x) row[x] /= std::max(min_white, w[x] * inverse_peak);
  }
}

}  // namespace lfsp::decode
