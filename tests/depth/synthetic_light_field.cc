#include "synthetic_light_field.h"

#include <cmath>
#include <cstdint>

#include "lfsp/core/metadata.h"

namespace lfsp::depth::testing {
namespace {

float Hash(int x, int y, std::uint32_t seed) {
  std::uint32_t h = static_cast<std::uint32_t>(x) * 374761393u + static_cast<std::uint32_t>(y) * 668265263u + seed;
  h = (h ^ (h >> 13)) * 1274126177u;
  h ^= h >> 16;
  return static_cast<float>(h & 0xffffu) / 65535.0f;
}

// Bilinear value noise with lattice spacing `cell` pixels, in [0, 1].
float ValueNoise(float x, float y, float cell, std::uint32_t seed) {
  const float gx = x / cell;
  const float gy = y / cell;
  const int ix = static_cast<int>(std::floor(gx));
  const int iy = static_cast<int>(std::floor(gy));
  const float fx = gx - static_cast<float>(ix);
  const float fy = gy - static_cast<float>(iy);
  const float top = Hash(ix, iy, seed) * (1 - fx) + Hash(ix + 1, iy, seed) * fx;
  const float bottom = Hash(ix, iy + 1, seed) * (1 - fx) + Hash(ix + 1, iy + 1, seed) * fx;
  return top * (1 - fy) + bottom * fy;
}

// Two octaves per channel around `base`, scaled by `contrast`.
void Texture(float x, float y, std::uint32_t seed, float base, float contrast, float* rgb) {
  for (int c = 0; c < 3; ++c) {
    const std::uint32_t s = seed * 7u + static_cast<std::uint32_t>(c);
    rgb[c] = base + contrast * (0.25f * ValueNoise(x, y, 4.0f, s) + 0.15f * ValueNoise(x, y, 1.7f, s + 100u));
  }
}

}  // namespace

ShiftLightField MakeShiftLightField(const ShiftScene& scene) {
  LightFieldShape shape;
  shape.nu = shape.nv = scene.views;
  shape.width = shape.height = scene.size;
  shape.channels = 3;
  ShiftLightField out{LightField(shape), DisparityMap(scene.size, scene.size)};
  const ViewIndex centre = shape.Centre();
  const float lo = static_cast<float>(scene.size) / 3.0f;
  const float hi = 2.0f * static_cast<float>(scene.size) / 3.0f;
  auto in_square = [&](float x, float y) { return x >= lo && x < hi && y >= lo && y < hi; };
  for (int v = 0; v < shape.nv; ++v) {
    for (int u = 0; u < shape.nu; ++u) {
      const float du = static_cast<float>(u - centre.u);
      const float dv = static_cast<float>(v - centre.v);
      for (int y = 0; y < shape.height; ++y) {
        for (int x = 0; x < shape.width; ++x) {
          // The view pixel (x, y) sees centre position (x + du d, y + dv d) of the surface at disparity d.
          const float fx = static_cast<float>(x) + du * scene.foreground;
          const float fy = static_cast<float>(y) + dv * scene.foreground;
          float* rgb = &out.light_field.at({u, v}, y, x, 0);
          if (in_square(fx, fy)) {
            Texture(fx, fy, 2u, 0.45f, 1.0f, rgb);
          } else {
            Texture(static_cast<float>(x) + du * scene.background, static_cast<float>(y) + dv * scene.background, 1u,
                    0.15f, scene.background_contrast, rgb);
          }
        }
      }
    }
  }
  for (int y = 0; y < scene.size; ++y) {
    for (int x = 0; x < scene.size; ++x) {
      out.disparity.at(y, x) =
          in_square(static_cast<float>(x), static_cast<float>(y)) ? scene.foreground : scene.background;
    }
  }
  SetDisparityRange(out.light_field.metadata, {scene.background - 0.5f, scene.foreground + 0.5f});
  return out;
}

}  // namespace lfsp::depth::testing
