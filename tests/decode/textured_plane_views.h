#pragma once

// The synthetic light field the per-view gain tests (lattice_gain_test.cc, jpeg_block_gain_test.cc) put a known gain
// on: 5 x 5 views of 240 x 180 pixels seeing a textured plane at disparity 0.7, channels scaled 0.8, 1.0, 1.2, every
// ray weight 1. Each test brings its own texture and gain.

#include <cmath>

#include "lfsp/core/light_field.h"

namespace lfsp::decode::testing {

// `texture(x, y)`: the plane's brightness at centre-view position (x, y); `gain(u, v, x, y, c)`: the factor put on
// view (u, v)'s pixel (x, y), channel c.
template <class Texture, class Gain>
LightField TexturedPlaneViews(const Texture& texture, const Gain& gain) {
  LightFieldShape shape;
  shape.nu = shape.nv = 5;
  shape.width = 240;
  shape.height = 180;
  shape.channels = 3;
  LightField light_field(shape);
  light_field.EnableWeights(1.0f);
  const double disparity = 0.7;
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u)
      for (int y = 0; y < shape.height; ++y)
        for (int x = 0; x < shape.width; ++x) {
          const float value = texture(x + disparity * (u - 2), y + disparity * (v - 2));
          for (int c = 0; c < 3; ++c)
            light_field.at({u, v}, y, x, c) = static_cast<float>(value * (0.8 + 0.2 * c) * gain(u, v, x, y, c));
        }
  return light_field;
}

// The rms of a / b - 1 over every view's pixels 10 or more from the border, channels first_channel..last_channel.
inline double RatioRms(const LightField& a, const LightField& b, int first_channel, int last_channel) {
  const LightFieldShape& shape = a.shape();
  double squares = 0.0;
  long count = 0;
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u)
      for (int y = 10; y < shape.height - 10; ++y)
        for (int x = 10; x < shape.width - 10; ++x)
          for (int c = first_channel; c <= last_channel; ++c) {
            const double e = a.at({u, v}, y, x, c) / b.at({u, v}, y, x, c) - 1.0;
            squares += e * e;
            ++count;
          }
  return std::sqrt(squares / static_cast<double>(count));
}

}  // namespace lfsp::decode::testing
