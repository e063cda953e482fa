#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"

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

// Every view of a decoded light field registered against the same view of its ideal light field (MeasureShift on
// grey views), for the views whose mean weight in the ideal one is above `min_weight`; the others are skipped.
struct ViewShift {
  ViewIndex view;
  double weight = 0.0;  // mean weight of the view in the ideal light field
  bool registered = false;
  Shift2D shift;
};
struct ViewRegistration {
  std::vector<ViewShift> views;  // every view, in camera-number order
  int registered = 0;
  double worst = 0.0;  // largest |dx| or |dy| over the registered views, px
};
ViewRegistration RegisterViews(const LightField& decoded, const LightField& truth, double min_weight, int margin);

}  // namespace lfsp
