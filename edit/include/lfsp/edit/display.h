#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp::edit {

// A copy of `image` (float, values in the given transfer encoding) ready for an 8/16-bit preview: linear values are
// encoded with the sRGB curve, and everything is clamped to [0, 1].
cv::Mat ToDisplay(const cv::Mat& image, Transfer transfer);

}  // namespace lfsp::edit
