#include "lfsp/depth/noise_matched_kernel.h"

#include <algorithm>
#include <cmath>

namespace lfsp::depth {

std::array<float, 4> NoiseMatchedWeights(float a) {
  const double s = a, r = 1.0 - s;
  const std::array<double, 4> spline = {r * r * r / 6.0, (3.0 * s * s * s - 6.0 * s * s + 4.0) / 6.0,
                                        (-3.0 * s * s * s + 3.0 * s * s + 3.0 * s + 1.0) / 6.0, s * s * s / 6.0};
  constexpr std::array<double, 4> third_difference = {-1.0, 3.0, -3.0, 1.0};
  // Gain of spline + t * third_difference: gain(t) = |spline|^2 + 2 t (spline . d) + 20 t^2 (|d|^2 = 20). Solve
  // gain(t) = kNoiseMatchedGain for the root nearer 0 (the least change to the spline).
  double dot = 0.0, gain = 0.0;
  for (int k = 0; k < 4; ++k) {
    dot += spline[k] * third_difference[k];
    gain += spline[k] * spline[k];
  }
  const double excess = gain - static_cast<double>(kNoiseMatchedGain);
  const double root = std::sqrt(std::max(0.0, dot * dot - 20.0 * excess));
  const double t = dot > 0.0 ? (-dot + root) / 20.0 : (-dot - root) / 20.0;
  std::array<float, 4> weights{};
  for (int k = 0; k < 4; ++k) weights[k] = static_cast<float>(spline[k] + t * third_difference[k]);
  return weights;
}

std::array<float, 4> CubicConvolutionWeights(float a) {
  const float s = a, r = 1.0f - a;
  return {-0.5f * s * r * r, 1.0f - 2.5f * s * s + 1.5f * s * s * s, 1.0f - 2.5f * r * r + 1.5f * r * r * r,
          -0.5f * r * s * s};
}

}  // namespace lfsp::depth
