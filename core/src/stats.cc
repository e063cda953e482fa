#include "lfsp/core/stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lfsp/core/ordered_reduction.h"

namespace lfsp {

namespace {

// Range and sum of a run of values, skipping non-finite ones.
struct Partial {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  double sum = 0.0;
  std::size_t finite = 0;
  std::size_t non_finite = 0;
};

}  // namespace

ValueStats ComputeStats(const float* values, std::size_t count, std::size_t stride) {
  // Chunks of values summed in a fixed order (OrderedParallelSum): the mean has the same bits on every run and
  // thread count, which an OpenMP reduction of a double does not promise.
  constexpr std::size_t kChunk = std::size_t{1} << 16;
  const auto chunks = static_cast<int>((count + kChunk - 1) / kChunk);
  const Partial total = OrderedParallelSum(
      chunks, [] { return Partial{}; },
      [&](int chunk, Partial& partial) {
        const std::size_t begin = static_cast<std::size_t>(chunk) * kChunk;
        const std::size_t end = std::min(count, begin + kChunk);
        for (std::size_t i = begin; i < end; ++i) {
          const double value = values[i * stride];
          if (!std::isfinite(value)) {
            ++partial.non_finite;
            continue;
          }
          partial.lo = std::min(partial.lo, value);
          partial.hi = std::max(partial.hi, value);
          partial.sum += value;
          ++partial.finite;
        }
      },
      [](Partial& into, const Partial& from) {
        into.lo = std::min(into.lo, from.lo);
        into.hi = std::max(into.hi, from.hi);
        into.sum += from.sum;
        into.finite += from.finite;
        into.non_finite += from.non_finite;
      });
  ValueStats stats;
  stats.count = total.finite;
  stats.non_finite = total.non_finite;
  if (total.finite > 0) {
    stats.min = total.lo;
    stats.max = total.hi;
    stats.mean = total.sum / static_cast<double>(total.finite);
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
