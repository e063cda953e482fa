#pragma once

// Shearing a light field: what refocusing does to the views, and the operation behind the LFSP paper's refocus sweep
// (Section V-A.5), whose refocus level L is a shear by -L (segment::RefocusLightField): disparities grow by L there.
//
// Shearing by s translates every view (u, v) by ((u-uc)*s, (v-vc)*s):
//   out(u, v)(x, y) = in(u, v)(x - (u-uc)*s, y - (v-vc)*s).
// With the docs/DESIGN.md convention (centre pixel (x, y) at disparity d appears in view (u, v) at
// (x - (u-uc)*d, y - (v-vc)*d)), a scene point at disparity s becomes aligned across views, and every disparity
// decreases by s. Shearing by -s undoes a shear by s (up to interpolation error and the lost borders).

#include <opencv2/core/mat.hpp>

#include "lfsp/core/conventions.h"
#include "lfsp/core/light_field.h"

namespace lfsp {

enum class ShearInterpolation {
  kLinear,  // bilinear: cheap, slightly blurs at fractional shifts
  kCubic,   // Keys cubic (a = -0.5): sharper, may overshoot by a few percent at edges (not clamped)
};

// What a sample whose source lies outside the view takes.
enum class ShearBorder {
  kReplicate,  // the nearest edge pixel
  kZero,       // zero
};

// A translation in pixels: out(x, y) = in(x - dx, y - dy).
struct ImageShift {
  float dx = 0.0f;
  float dy = 0.0f;
};

// The translation of view `view` in a shear by `disparity`: ((u-uc)*s, (v-vc)*s).
constexpr ImageShift ShearShift(ViewIndex view, ViewIndex centre, float disparity) {
  return {static_cast<float>(view.u - centre.u) * disparity, static_cast<float>(view.v - centre.v) * disparity};
}

// Translates `in` (CV_32FC(n), n = 1..4) by `shift` with sub-pixel interpolation into `out` (allocated to in's
// size and type if needed; must not share memory with `in`). OpenMP-parallel over rows.
void TranslateImage(const cv::Mat& in, ImageShift shift, cv::Mat& out,
                    ShearInterpolation interpolation = ShearInterpolation::kLinear,
                    ShearBorder border = ShearBorder::kReplicate);

// Translates a label image (CV_32SC1) by `shift` with nearest-neighbour sampling (the source position rounded,
// halves rounding up); samples whose source lies outside take Labels::kUnlabelled.
void TranslateLabels(const cv::Mat& in, ImageShift shift, cv::Mat& out);

struct ShearOptions {
  ShearInterpolation interpolation = ShearInterpolation::kLinear;
  // true: the result carries per-ray weights: the input's weights (1 where it has none), translated bilinearly
  // with zero outside the view, so rays whose source lay outside a view get weight 0 (their colour replicates the
  // edge). false: weights are carried over only if the input has them (still zero outside).
  bool weight_outside = true;
};

// The light field sheared by `disparity` (see the top of this file). Transfer and metadata are copied.
LightField ShearLightField(const LightField& light_field, float disparity, const ShearOptions& options = {});

// Labels sheared by `disparity` with nearest-neighbour sampling; -1 where the source lies outside the view.
Labels ShearLabels(const Labels& labels, float disparity);

// The centre-view disparity map of the sheared light field: every value minus `disparity` (the centre view does not
// move). Non-finite values stay as they are.
DisparityMap ShearDisparity(const DisparityMap& disparity_map, float disparity);

}  // namespace lfsp
