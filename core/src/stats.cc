#include "lfsp/core/stats.h"

#include <cmath>
#include <limits>

namespace lfsp {

ValueStats ComputeStats(const float* values, std::size_t count, std::size_t stride) {
  ValueStats stats;
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  double sum = 0.0;
  std::size_t finite = 0;
  std::size_t non_finite = 0;
  const auto n = static_cast<long long>(count);
#pragma omp parallel for reduction(min : lo) reduction(max : hi) reduction(+ : sum, finite, non_finite)
  for (long long i = 0; i < n; ++i) {
    const double value = values[static_cast<std::size_t>(i) * stride];
    if (!std::isfinite(value)) {
      ++non_finite;
      continue;
    }
    lo = std::min(lo, value);
    hi = std::max(hi, value);
    sum += value;
    ++finite;
  }
  stats.count = finite;
  stats.non_finite = non_finite;
  if (finite > 0) {
    stats.min = lo;
    stats.max = hi;
    stats.mean = sum / static_cast<double>(finite);
  }
  return stats;
}

ValueStats ChannelStats(const LightField& light_field, int channel) {
  const auto channels = static_cast<std::size_t>(light_field.shape().channels);
  return ComputeStats(light_field.data() + channel, light_field.size() / channels, channels);
}

ValueStats DisparityStats(const DisparityMap& disparity) {
  return ComputeStats(disparity.data(), static_cast<std::size_t>(disparity.width()) * disparity.height());
}

}  // namespace lfsp
