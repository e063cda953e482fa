#include "lfsp/core/srgb.h"
#include "lfsp/core/srgb_table.h"

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

const SrgbTable& SrgbToLinearTable() {
  static const SrgbTable table = [] {
    SrgbTable t{};
    for (int i = 0; i <= kSrgbTableSegments; ++i)
      t[static_cast<std::size_t>(i)] = static_cast<float>(SrgbToLinear(static_cast<double>(i) / kSrgbTableSegments));
    return t;
  }();
  return table;
}

float SrgbToLinearTabulated(float encoded) { return SrgbToLinearTabulated(encoded, SrgbToLinearTable()); }

}  // namespace lfsp
