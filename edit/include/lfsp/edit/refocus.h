#pragma once

// Shift-and-sum refocusing: focal stacks and all-in-focus images (the sheared light field itself, the "refocus
// level" operation, is in lfsp/core/shear.h).

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/core/shear.h"

namespace lfsp::edit {

struct RefocusOptions {
  ShearInterpolation interpolation = ShearInterpolation::kLinear;
  bool use_ray_weights = true;  // weight each ray by the light field's per-ray weights, when it has them
};

// The image focused at `disparity` (pixels per view step): each centre-view pixel (x, y) is the weighted mean over
// all views of the ray at (x - (u-uc)*s, y - (v-vc)*s), i.e. the mean of the light field sheared by s. Rays whose
// position falls outside their view are left out (their weight fades to zero over the last pixel). Returns an
// H x W image of the light field's type (CV_32FC(channels)) in the light field's transfer encoding.
cv::Mat RefocusImage(const LightField& light_field, float disparity, const RefocusOptions& options = {});

// One refocused image per disparity.
std::vector<cv::Mat> FocalStack(const LightField& light_field, const std::vector<float>& disparities,
                                const RefocusOptions& options = {});

// `count` disparities evenly spaced from `min` to `max` inclusive (one: their midpoint). Throws lfsp::Error if
// count < 1 or the range is not finite or min > max.
std::vector<float> EvenlySpacedDisparities(float min, float max, int count);

struct AllInFocusOptions {
  bool use_ray_weights = true;
  // Leave out, per view, the rays that something nearer hides: a centre pixel at disparity d is taken as occluded
  // in view (u, v) when another centre pixel with disparity above d + occlusion_tolerance lands on the same pixel of
  // that view. Without this, pixels beside a foreground edge mix in the foreground's colour.
  bool occlusion_aware = true;
  float occlusion_tolerance = 0.5f;  // pixels per view step
};

// The all-in-focus image: each centre-view pixel is the weighted mean of the rays along its disparity line,
// (x - (u-uc)*d(x, y), y - (v-vc)*d(x, y)) for every view, bilinearly sampled; rays outside a view (and occluded
// ones, see the options) are left out. Pixels with a non-finite disparity keep the centre view's value. The
// disparity map must have the light field's view size. Equivalent to taking, per pixel, the refocused value at its
// own disparity (plus occlusion handling).
cv::Mat AllInFocus(const LightField& light_field, const DisparityMap& disparity, const AllInFocusOptions& options = {});

}  // namespace lfsp::edit
