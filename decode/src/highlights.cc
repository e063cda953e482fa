#include "highlights.h"

#include <algorithm>
#include <limits>

#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

// Rows per band, and the rows of context above and below it that the demosaic's 5 x 5 kernels read (even, so every
// band starts on the same Bayer phase as the sensor).
constexpr int kBandRows = 256;
constexpr int kBandMargin = 4;

// Limits the channels of `pixel` where one of them reached its ceiling; true when it changed a value.
bool Neutralise(float* pixel, const float* ceiling, const float* gain, float clipped_fraction) {
  float level = std::numeric_limits<float>::infinity();  // white-balanced
  for (int c = 0; c < 3; ++c)
    if (ceiling[c] > 0.0f && pixel[c] >= clipped_fraction * ceiling[c]) level = std::min(level, ceiling[c] * gain[c]);
  if (level == std::numeric_limits<float>::infinity()) return false;
  bool limited = false;
  for (int c = 0; c < 3; ++c) {
    const float limit = level / gain[c];
    if (pixel[c] > limit) {
      pixel[c] = limit;
      limited = true;
    }
  }
  return limited;
}

}  // namespace

long NeutraliseClippedHighlights(cv::Mat& rgb, const cv::Mat& inverse_white, BayerPattern pattern,
                                 DemosaicMethod method, const MicroImages& micro_images,
                                 const std::array<double, 3>& gains, float clipped_fraction) {
  if (rgb.type() != CV_32FC3 || inverse_white.type() != CV_32FC1 || rgb.size() != inverse_white.size())
    throw Error("decode: the white image must match the demosaiced image to find its clipped highlights");
  const float gain[3] = {static_cast<float>(gains[0]), static_cast<float>(gains[1]), static_cast<float>(gains[2])};
  long changed = 0;
  for (int begin = 0; begin < rgb.rows; begin += kBandRows) {
    const int end = std::min(rgb.rows, begin + kBandRows);
    const int top = std::max(0, begin - kBandMargin), bottom = std::min(rgb.rows, end + kBandMargin);
    const cv::Mat grey = micro_images.white_grey.rowRange(top, bottom);
    const cv::Mat labels = micro_images.lens_labels.rowRange(top, bottom);
    const MicroImages band_images{grey, labels};
    const cv::Mat ceilings = Demosaic(inverse_white.rowRange(top, bottom), pattern, method, 4.0f, &band_images);
#pragma omp parallel for schedule(static) reduction(+ : changed)
    for (int y = begin; y < end; ++y) {
      float* pixel = rgb.ptr<float>(y);
      const float* ceiling = ceilings.ptr<float>(y - top);
      for (int x = 0; x < rgb.cols; ++x)
        if (Neutralise(pixel + 3 * x, ceiling + 3 * x, gain, clipped_fraction)) ++changed;
    }
  }
  return changed;
}

}  // namespace lfsp::decode
