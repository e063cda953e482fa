// OrderedParallelSum must give the same bits whatever the thread count: the sums here are of floats whose rounding
// depends on the order of the additions, so a merge in thread-finishing order (or over a schedule-dependent split)
// would make them differ.

#include "lfsp/core/ordered_reduction.h"
#include "lfsp/core/stats.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

namespace lfsp {
namespace {

// Items whose float sum is order-sensitive: magnitudes spread over many binades.
float Item(int i) { return std::ldexp(1.0f + 0.37f * static_cast<float>(i % 7), (i * 13) % 40 - 20); }

float SumWithThreads(int count, int threads) {
  omp_set_num_threads(threads);
  return OrderedParallelSum(
      count, [] { return 0.0f; }, [](int i, float& partial) { partial += Item(i); },
      [](float& into, const float& from) { into += from; });
}

// The same additions, one block after another, in one thread.
float SerialBlockSum(int count, int blocks) {
  float total = 0.0f;
  for (int b = 0; b < blocks; ++b) {
    float partial = 0.0f;
    for (long long i = static_cast<long long>(count) * b / blocks; i < static_cast<long long>(count) * (b + 1) / blocks;
         ++i)
      partial += Item(static_cast<int>(i));
    total = b == 0 ? partial : total + partial;
  }
  return total;
}

bool SameBits(float a, float b) { return std::memcmp(&a, &b, sizeof(float)) == 0; }

TEST(OrderedParallelSum, SameBitsForEveryThreadCount) {
  const int previous = omp_get_max_threads();
  for (const int count : {1, 3, 8, 81, 225, 1000}) {
    const float expected = SerialBlockSum(count, std::min(count, kOrderedReductionBlocks));
    for (const int threads : {1, 2, 3, 5, 8}) {
      for (int repeat = 0; repeat < 5; ++repeat) {
        const float got = SumWithThreads(count, threads);
        EXPECT_TRUE(SameBits(got, expected))
            << count << " items, " << threads << " threads: " << got << " vs " << expected;
      }
    }
  }
  omp_set_num_threads(previous);
}

TEST(OrderedParallelSum, TheOrderMatters) {
  // Guards the test above: if these items summed to the same bits in any order, it could not fail.
  float forward = 0.0f, backward = 0.0f;
  for (int i = 0; i < 1000; ++i) forward += Item(i);
  for (int i = 999; i >= 0; --i) backward += Item(i);
  EXPECT_FALSE(SameBits(forward, backward));
}

TEST(OrderedParallelSum, NoItemsGiveAnEmptyPartial) {
  int calls = 0;
  const double sum = OrderedParallelSum(
      0, [] { return 0.0; }, [&](int, double&) { ++calls; }, [](double& into, const double& from) { into += from; });
  EXPECT_EQ(sum, 0.0);
  EXPECT_EQ(calls, 0);
}

TEST(OrderedParallelSum, EveryItemOnce) {
  std::vector<int> seen(500, 0);
  const long long sum = OrderedParallelSum(
      500, [] { return 0LL; },
      [&](int i, long long& partial) {
        partial += i;
        ++seen[static_cast<std::size_t>(i)];  // each item belongs to one block, so no two threads write it
      },
      [](long long& into, const long long& from) { into += from; });
  EXPECT_EQ(sum, 500LL * 499 / 2);
  for (const int count : seen) EXPECT_EQ(count, 1);
}

// ComputeStats sums through OrderedParallelSum: exact counts, range and mean over several chunks (65,536 values
// each) with non-finite values and a stride, and the same bits for any thread count.
TEST(ComputeStats, CountsRangeAndMeanAcrossChunksForEveryThreadCount) {
  constexpr std::size_t kCount = 200003;            // three full chunks and a partial one
  std::vector<float> values(2 * kCount, -1000.0f);  // stride 2: the odd entries must be ignored
  double expected_sum = 0.0;
  std::size_t expected_finite = 0;
  for (std::size_t i = 0; i < kCount; ++i) {
    float value = Item(static_cast<int>(i));
    if (i % 1009 == 0) value = std::numeric_limits<float>::quiet_NaN();
    if (i % 2003 == 0) value = std::numeric_limits<float>::infinity();
    if (i == 77777) value = -3.5f;
    values[2 * i] = value;
    if (std::isfinite(value)) {
      expected_sum += value;
      ++expected_finite;
    }
  }
  const int previous = omp_get_max_threads();
  omp_set_num_threads(1);
  const ValueStats reference = ComputeStats(values.data(), kCount, 2);
  EXPECT_EQ(reference.count, expected_finite);
  EXPECT_EQ(reference.non_finite, kCount - expected_finite);
  EXPECT_EQ(reference.min, -3.5);
  EXPECT_NEAR(reference.mean, expected_sum / static_cast<double>(expected_finite), 1e-9 * std::abs(reference.mean));
  for (const int threads : {2, 3, 5}) {
    omp_set_num_threads(threads);
    const ValueStats again = ComputeStats(values.data(), kCount, 2);
    EXPECT_EQ(std::memcmp(&again.mean, &reference.mean, sizeof(double)), 0) << threads << " threads";
    EXPECT_EQ(again.max, reference.max);
    EXPECT_EQ(again.count, reference.count);
  }
  omp_set_num_threads(previous);
}

}  // namespace
}  // namespace lfsp
