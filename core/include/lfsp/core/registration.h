#pragma once

#include <opencv2/core/mat.hpp>

namespace lfsp {

// The sub-pixel translation (dx, dy) that takes `reference` to `moving` (moving(x) ~ reference(x - d)), by least
// squares on the reference's gradients (first-order Lucas-Kanade, with a gain and an offset fitted too, so an
// exposure difference does not read as a shift). Both are single-channel float images of one size; `margin`
// pixels at each border are left out. Accurate for shifts well below a pixel: it measures how two renderings of
// the same view differ, not a disparity.
struct Shift2D {
  double dx = 0.0;
  double dy = 0.0;
};
Shift2D MeasureShift(const cv::Mat& reference, const cv::Mat& moving, int margin);

// The mean of the three channels of an RGB float view, for MeasureShift.
cv::Mat GreyOf(const cv::Mat& rgb);

}  // namespace lfsp
