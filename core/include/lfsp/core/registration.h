#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp {

// The sub-pixel translation (dx, dy) that takes `reference` to `moving` (moving(x) ~ reference(x - d)), by least
// squares on the reference's gradients (first-order Lucas-Kanade, with a gain and an offset fitted too, so an
// exposure difference does not read as a shift). Both are single-channel float images of one size; `margin`
// pixels at each border are left out. Accurate for shifts well below a pixel: it measures how two renderings of
// the same view differ, not a disparity. With `mask` (CV_8U, the images' size), only its nonzero pixels count.
struct Shift2D {
  double dx = 0.0;
  double dy = 0.0;
};
Shift2D MeasureShift(const cv::Mat& reference, const cv::Mat& moving, int margin, const cv::Mat& mask = cv::Mat());

// The mean of the three channels of an RGB float view, for MeasureShift.
cv::Mat GreyOf(const cv::Mat& rgb);

// The same in linear light: an sRGB-encoded view is decoded first. A gain and an offset cannot absorb the sRGB
// curve, so comparing an encoded view with a linear one would read its brightness changes as shifts.
cv::Mat LinearGreyOf(const cv::Mat& rgb, Transfer transfer);

// Every view of a decoded light field registered against the same view of its ideal light field (MeasureShift on
// linear grey views, each decoded by its light field's transfer), for the views whose mean weight in the ideal one is
// above `min_weight`; the others are skipped. With `mask` (CV_8U, the views' size), only its nonzero pixels count:
// near depth edges the views differ by what each occludes, which a single shift cannot describe.
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
ViewRegistration RegisterViews(const LightField& decoded, const LightField& truth, double min_weight, int margin,
                               const cv::Mat& mask = cv::Mat());

// The same a block of views at a time, for a caller that cannot hold the whole ideal light field beside the decoded
// one (the pipeline reads the simulator's 1 GB truth a row of views at a time): `truth_views` holds the ideal light
// field's views from view `first` on (a block of it, with its weights), and each of them is registered against the
// same view of `decoded` into `result.views` (sized to all of decoded's views beforehand). CountRegistered then
// gives the count and the worst shift. The figures are RegisterViews's, whatever the blocks.
void RegisterBlock(const LightField& decoded, const LightField& truth_views, ViewIndex first, double min_weight,
                   int margin, const cv::Mat& mask, ViewRegistration& result);
void CountRegistered(ViewRegistration& registration);

}  // namespace lfsp
