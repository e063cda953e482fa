#pragma once

#include "lfsp/core/light_field.h"

namespace lfsp::depth::testing {

// A tiny shift-based light field with exact ground truth: a textured fronto-parallel background plane at
// `background` disparity and a textured square (the middle third of the image) in front of it at `foreground`
// disparity. Every view pixel is rendered by looking up which surface the ray meets (the square occludes), and
// evaluating that surface's smooth value-noise texture at the continuous centre-view position, so views differ by
// exact sub-pixel shifts and occlusions are geometrically right. As in the HCI scenes, the background is dim and
// faintly textured and the occluder bright, which is where occlusion handling matters.
struct ShiftScene {
  int views = 9;  // views per side
  int size = 96;  // pixels per side
  float background = -1.0f;
  float foreground = 1.2f;
  float background_contrast = 0.25f;  // texture amplitude of the (dimmer) background; the square's is 1
};

struct ShiftLightField {
  LightField light_field;  // metadata carries disp_min/disp_max = the scene's range widened by 0.5
  DisparityMap disparity;  // centre-view ground truth
};

ShiftLightField MakeShiftLightField(const ShiftScene& scene);

}  // namespace lfsp::depth::testing
