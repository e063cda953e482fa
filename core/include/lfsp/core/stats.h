#pragma once

#include <cstddef>

#include "lfsp/core/light_field.h"

namespace lfsp {

// Minimum, maximum and mean of a set of samples, ignoring NaN and infinities (counted separately).
struct ValueStats {
  double min = 0.0;
  double max = 0.0;
  double mean = 0.0;
  std::size_t count = 0;
  std::size_t non_finite = 0;
};

ValueStats ComputeStats(const float* values, std::size_t count, std::size_t stride = 1);
ValueStats ChannelStats(const LightField& light_field, int channel);
ValueStats DisparityStats(const DisparityMap& disparity);

}  // namespace lfsp
