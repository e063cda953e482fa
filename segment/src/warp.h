#pragma once

#include <cstdint>
#include <vector>

namespace lfsp::segment {

// How far (px per view step) two disparities may differ and still be the same scene surface: well above the rounding
// of one pixel on slanted surfaces, well below an occlusion step. Used wherever labels are carried along disparity.
constexpr float kSameSurfaceTolerance = 0.25f;

// Forward projection of centre-view samples into the view at offset (du, dv) = (u - uc, v - vc), docs/DESIGN.md
// convention: centre pixel (x0, y0) with disparity d lands at (x0 - du d, y0 - dv d), rounded to the nearest pixel.
// Where several land on one pixel the largest disparity (front-most) wins. Pixels nothing lands on keep label -1 and
// depth -infinity. `centre_labels` and `centre_disparity` are width x height, row-major.
void ForwardWarp(const std::int32_t* centre_labels, const float* centre_disparity, int width, int height, int du,
                 int dv, std::int32_t* view_labels, float* view_depth);

// Fills the pixels with label -1 left by ForwardWarp. A hole in a side view is a surface the centre view does not
// see (disocclusion) or a rounding gap, so each takes the label and depth of the nearest labelled pixel along its
// epipolar line on the background side (the smaller disparity of the two nearest along the line). Holes with no
// labelled pixel along the line within reach (image borders) take the nearest labelled pixel (4-connected
// breadth-first). Does nothing if no pixel is labelled.
void FillHoles(std::int32_t* view_labels, float* view_depth, int width, int height, int du, int dv, int max_steps);

// FillHoles' max_steps for the view at (du, dv) when the centre disparities reach +-max_abs: twice the largest shift
// plus two, at most 512. Capped before the conversion to int, which a disparity of 1e38 or infinity would overflow.
int FillReach(float max_abs, int du, int dv);

}  // namespace lfsp::segment
