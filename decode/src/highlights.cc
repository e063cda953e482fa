#include "highlights.h"

#include <algorithm>
#include <limits>

#include "lfsp/core/error.h"

namespace lfsp::decode {

long NeutraliseClippedHighlights(cv::Mat& rgb, const cv::Mat& ceilings, const std::array<double, 3>& gains,
                                 float clipped_fraction) {
  if (rgb.type() != CV_32FC3 || ceilings.type() != CV_32FC3 || rgb.size() != ceilings.size())
    throw Error("decode: highlight ceilings must match the demosaiced image");
  const float gain[3] = {static_cast<float>(gains[0]), static_cast<float>(gains[1]), static_cast<float>(gains[2])};
  long changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed)
  for (int y = 0; y < rgb.rows; ++y) {
    float* pixel = rgb.ptr<float>(y);
    const float* ceiling = ceilings.ptr<float>(y);
    for (int x = 0; x < rgb.cols; ++x, pixel += 3, ceiling += 3) {
      float level = std::numeric_limits<float>::infinity();  // white-balanced
      for (int c = 0; c < 3; ++c)
        if (ceiling[c] > 0.0f && pixel[c] >= clipped_fraction * ceiling[c])
          level = std::min(level, ceiling[c] * gain[c]);
      if (level == std::numeric_limits<float>::infinity()) continue;
      bool limited = false;
      for (int c = 0; c < 3; ++c) {
        const float limit = level / gain[c];
        if (pixel[c] > limit) {
          pixel[c] = limit;
          limited = true;
        }
      }
      if (limited) ++changed;
    }
  }
  return changed;
}

}  // namespace lfsp::decode
