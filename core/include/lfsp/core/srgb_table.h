#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace lfsp {

// The table SrgbToLinearTabulated (srgb.h) interpolates in, for loops over many samples:
// SrgbToLinearTabulated(encoded, table) is inlined where the one-argument form is a call (and a check of the
// table's initialisation) per sample, and gives the same floats. Apart from srgb.h, which every light field's
// user includes, so that loops opting in are all that recompile.
constexpr int kSrgbTableSegments = 4096;
using SrgbTable = std::array<float, kSrgbTableSegments + 1>;
const SrgbTable& SrgbToLinearTable();

inline float SrgbToLinearTabulated(float encoded, const SrgbTable& table) {
  const float f = std::clamp(encoded, 0.0f, 1.0f) * kSrgbTableSegments;
  const int i = std::min(static_cast<int>(f), kSrgbTableSegments - 1);
  const float w = f - static_cast<float>(i);
  return table[static_cast<std::size_t>(i)] * (1.0f - w) + table[static_cast<std::size_t>(i) + 1] * w;
}

}  // namespace lfsp
