// The semi-global penalties follow the range of the cost they regularise (PenaltiesForCost).

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <random>

#include "lfsp/depth/cost_volume.h"
#include "lfsp/depth/sgm.h"

namespace lfsp::depth {
namespace {

TEST(PenaltiesForCost, TheDefaultCostKeepsThePenaltiesGiven) {
  const SgmOptions given{0.2f, 1.5f, 0.03f};
  const SgmOptions used = PenaltiesForCost(given, CostOptions());
  EXPECT_FLOAT_EQ(used.p1, 0.2f);
  EXPECT_FLOAT_EQ(used.p2, 1.5f);
  EXPECT_FLOAT_EQ(used.edge_sigma, 0.03f);
  EXPECT_NEAR(CostRange(CostOptions()), 0.86f, 1e-6f);
}

TEST(PenaltiesForCost, ACostWithoutItsDetailTermGetsPenaltiesInProportion) {
  CostOptions colour_only;
  colour_only.detail_weight = 0.0f;  // what the automatic weight gives full-size lenslet decodes
  const SgmOptions used = PenaltiesForCost(SgmOptions(), colour_only);
  EXPECT_NEAR(used.p1, 0.1f * 0.36f / 0.86f, 1e-6f);
  EXPECT_NEAR(used.p2, 1.0f * 0.36f / 0.86f, 1e-6f);
  CostOptions no_detail_band;
  no_detail_band.detail_sigma = 0.0f;  // no detail term at all, whatever its weight says
  EXPECT_FLOAT_EQ(PenaltiesForCost(SgmOptions(), no_detail_band).p2, used.p2);
  CostOptions heavier_colour;
  heavier_colour.colour_weight = 6.0f;
  EXPECT_NEAR(PenaltiesForCost(SgmOptions(), heavier_colour).p2, (6.0f * 0.12f + 0.5f) / 0.86f, 1e-6f);
}

// Aggregation is linear in the cost and the penalties together: a cost scaled by its range with the penalties
// scaled alike aggregates to the same volume scaled, so every pixel keeps its disparity.
TEST(PenaltiesForCost, ScalingTheCostAndItsPenaltiesTogetherKeepsTheBalance) {
  constexpr int kWidth = 24, kHeight = 16, kLabels = 9;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 0.86f);
  CostVolume full(kWidth, kHeight, kLabels);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int d = 0; d < kLabels; ++d) full.Curve(y, x)[d] = uniform(random);
  cv::Mat guide(kHeight, kWidth, CV_32FC3);
  cv::randu(guide, 0.0, 1.0);

  CostOptions colour_only;
  colour_only.detail_weight = 0.0f;
  const float scale = CostRange(colour_only) / CostRange(CostOptions());
  CostVolume scaled(kWidth, kHeight, kLabels);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      for (int d = 0; d < kLabels; ++d) scaled.Curve(y, x)[d] = scale * full.Curve(y, x)[d];

  const CostVolume expected = AggregateSemiGlobal(full, guide, SgmOptions());
  const CostVolume aggregated = AggregateSemiGlobal(scaled, guide, PenaltiesForCost(SgmOptions(), colour_only));
  const CostVolume unscaled_penalties = AggregateSemiGlobal(scaled, guide, SgmOptions());
  int moved_with_unscaled = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      for (int d = 0; d < kLabels; ++d)
        ASSERT_NEAR(aggregated.Curve(y, x)[d], scale * expected.Curve(y, x)[d], 1e-4f) << x << "," << y << "," << d;
      const auto argmin = [&](const CostVolume& v) {
        const float* curve = v.Curve(y, x);
        return static_cast<int>(std::min_element(curve, curve + kLabels) - curve);
      };
      moved_with_unscaled += argmin(unscaled_penalties) != argmin(expected);
    }
  }
  // The check can fail: with the penalties left as given, smoothness wins more often and pixels change label.
  EXPECT_GT(moved_with_unscaled, 0);
}

}  // namespace
}  // namespace lfsp::depth
