// The geometry of the occlusion handling: which views each subset of the angular patch holds, and how far from an
// edge it is used.

#include <gtest/gtest.h>

#include <numbers>

#include "lfsp/depth/occlusion.h"

namespace lfsp::depth {
namespace {

constexpr double kPi = std::numbers::pi;

// The views along an edge are those whose offsets are parallel to it, whichever way its gradient points.
TEST(Occlusion, ViewsAlongAnEdgeRunParallelToIt) {
  const int vertical = SectorOfOffset(0, 1) % (kSectors / 2);  // views straight above and below the centre
  const int horizontal = SectorOfOffset(1, 0) % (kSectors / 2);
  for (const double normal : {0.0, kPi, -kPi, 0.05, kPi - 0.05}) {  // a vertical edge: the gradient along x
    EXPECT_EQ(AlongPairForEdgeNormal(normal), vertical) << normal;
  }
  for (const double normal : {kPi / 2, -kPi / 2, kPi / 2 + 0.05, -kPi / 2 - 0.05}) {  // a horizontal edge
    EXPECT_EQ(AlongPairForEdgeNormal(normal), horizontal) << normal;
  }
  // A diagonal edge (gradient towards +x+y) runs along the offset (1, -1).
  EXPECT_EQ(AlongPairForEdgeNormal(kPi / 4), SectorOfOffset(1, -1) % (kSectors / 2));
}

TEST(Occlusion, AutomaticRadiusIsTheLargestShiftPlusTheBlur) {
  // 9x9 views: an outer view is 4 steps from the centre; a range of 2 px per step moves the background 8 px.
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(9, 9, -1.0f, 1.0f), 8.0);
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(9, 9, -1.0f, 1.0f, 2.5), 13.0);  // presmoothing spreads the edge 2 sigma
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(9, 9, -3.3f, 2.8f), kMaxAutomaticOcclusionRadius);
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(3, 3, 0.0f, 0.5f), 2.0);  // at least 2 px
}

}  // namespace
}  // namespace lfsp::depth
