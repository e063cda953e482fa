#include "lfsp/core/srgb.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace lfsp {

float LinearToSrgb(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

double LinearToSrgb(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

double SrgbToLinear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

float SrgbToLinearTabulated(float encoded) {
  constexpr int kSegments = 4096;
  static const std::array<float, kSegments + 1> table = [] {
    std::array<float, kSegments + 1> t{};
    for (int i = 0; i <= kSegments; ++i)
      t[static_cast<std::size_t>(i)] = static_cast<float>(SrgbToLinear(static_cast<double>(i) / kSegments));
    return t;
  }();
  const float f = std::clamp(encoded, 0.0f, 1.0f) * kSegments;
  const int i = std::min(static_cast<int>(f), kSegments - 1);
  const float w = f - static_cast<float>(i);
  return table[static_cast<std::size_t>(i)] * (1.0f - w) + table[static_cast<std::size_t>(i) + 1] * w;
}

}  // namespace lfsp
