#pragma once

// Analytic light fields for the edit tests: textured fronto-parallel planes whose every ray is known exactly, so
// refocusing and shearing can be checked against closed-form values (docs/DESIGN.md disparity convention).

#include <cmath>
#include <numbers>

#include "lfsp/core/light_field.h"

namespace lfsp::edit::testing {

// A smooth colour texture in centre-view pixel coordinates (several sinusoids, wavelengths 5.7 to 13 px), values in
// [0.1, 0.9]. `seed` changes phases and mixes so two planes look different.
inline float Texture(float x, float y, int channel, int seed) {
  constexpr float two_pi = 2.0f * std::numbers::pi_v<float>;
  const float phase = 0.9f * static_cast<float>(channel) + 1.7f * static_cast<float>(seed);
  const float value = 0.5f + 0.16f * std::sin(two_pi * x / (11.0f + 2.0f * seed) + phase) +
                      0.12f * std::sin(two_pi * y / (7.3f + seed) + 2.0f * phase) +
                      0.1f * std::sin(two_pi * (x + y) / 5.7f + 0.5f * phase);
  return value;
}

struct TwoPlaneScene {
  float background_disparity = -1.0f;
  float foreground_disparity = 1.5f;
  // Foreground rectangle in centre-view pixels [x0, x1) x [y0, y1); empty = background only.
  float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;

  bool InForeground(float cx, float cy) const { return cx >= x0 && cx < x1 && cy >= y0 && cy < y1; }
};

// Renders the scene by point-sampling the ray through each pixel centre: in view (u, v) the pixel (x, y) sees the
// foreground if (x + (u-uc) d_f, y + (v-vc) d_f) lies in its rectangle, else the background at disparity d_b.
inline LightField RenderPlanes(const TwoPlaneScene& scene, int n, int size, Labels* labels = nullptr,
                               DisparityMap* centre_disparity = nullptr) {
  LightFieldShape shape{n, n, size, size, 3};
  LightField light_field(shape);
  if (labels != nullptr) *labels = Labels(shape);
  if (centre_disparity != nullptr) *centre_disparity = DisparityMap(size, size);
  const ViewIndex centre = shape.Centre();
  for (int v = 0; v < n; ++v)
    for (int u = 0; u < n; ++u)
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const float du = static_cast<float>(u - centre.u);
          const float dv = static_cast<float>(v - centre.v);
          float cx = static_cast<float>(x) + du * scene.foreground_disparity;
          float cy = static_cast<float>(y) + dv * scene.foreground_disparity;
          int seed = 1;
          float d = scene.foreground_disparity;
          if (!scene.InForeground(cx, cy)) {
            cx = static_cast<float>(x) + du * scene.background_disparity;
            cy = static_cast<float>(y) + dv * scene.background_disparity;
            seed = 0;
            d = scene.background_disparity;
          }
          for (int c = 0; c < 3; ++c) light_field.at({u, v}, y, x, c) = Texture(cx, cy, c, seed);
          if (labels != nullptr) labels->at({u, v}, y, x) = seed;
          if (centre_disparity != nullptr && u == centre.u && v == centre.v) centre_disparity->at(y, x) = d;
        }
  return light_field;
}

// One textured plane at disparity d filling every view.
inline LightField RenderPlane(float disparity, int n, int size) {
  TwoPlaneScene scene;
  scene.background_disparity = disparity;
  return RenderPlanes(scene, n, size);
}

}  // namespace lfsp::edit::testing
