// Unit tests of lfsp/core/rounding.h: RoundHalfAway must round every double as std::lround does, since LFSP's
// refinement rounds plane disparities with it (a different rounding would move labels) and the white image estimated
// from a capture rounds its samples with it.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "lfsp/core/rounding.h"

namespace lfsp {
namespace {

TEST(RoundHalfAway, AgreesWithLroundOnHalvesAndTheirNeighbours) {
  for (double half = -40.5; half <= 40.5; half += 1.0) {
    for (const double x : {half, std::nextafter(half, -1e9), std::nextafter(half, 1e9)}) {
      EXPECT_EQ(RoundHalfAway(x), std::lround(x)) << x;
    }
  }
  // Just below one half: adding 0.5 in double rounds it up to 1, lround gives 0.
  EXPECT_EQ(RoundHalfAway(0.49999999999999994), 0);
  EXPECT_EQ(RoundHalfAway(-0.49999999999999994), 0);
  EXPECT_EQ(RoundHalfAway(4503599627370495.5 / 4194304.0), std::lround(4503599627370495.5 / 4194304.0));
}

TEST(RoundHalfAway, AgreesWithLroundOnRandomDisparities) {
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> disparity(-1100.0, 1100.0);
  for (int i = 0; i < 200000; ++i) {
    const double x = disparity(random);
    ASSERT_EQ(RoundHalfAway(x), std::lround(x)) << x;
  }
}

TEST(RoundHalfAway, ValuesBeyondAnyImageGiveTheSmallestInt) {
  EXPECT_EQ(RoundHalfAway(1e38), std::numeric_limits<int>::min());
  EXPECT_EQ(RoundHalfAway(-1e38), std::numeric_limits<int>::min());
  EXPECT_EQ(RoundHalfAway(std::numeric_limits<double>::quiet_NaN()), std::numeric_limits<int>::min());
}

}  // namespace
}  // namespace lfsp
