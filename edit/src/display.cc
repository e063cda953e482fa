#include "lfsp/edit/display.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"

namespace lfsp::edit {

cv::Mat ToDisplay(const cv::Mat& image, Transfer transfer) {
  if (image.empty() || image.depth() != CV_32F) throw Error("preview: expected a non-empty float image");
  cv::Mat out = image.clone();
  float* values = out.ptr<float>(0);
  const std::size_t count = out.total() * static_cast<std::size_t>(out.channels());
  for (std::size_t i = 0; i < count; ++i) {
    float value = std::min(1.0f, std::max(0.0f, values[i]));
    if (transfer == Transfer::kLinear)  // the sRGB encoding curve (IEC 61966-2-1)
      value = value <= 0.0031308f ? 12.92f * value : 1.055f * std::pow(value, 1.0f / 2.4f) - 0.055f;
    values[i] = value;
  }
  return out;
}

}  // namespace lfsp::edit
