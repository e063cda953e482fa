// HCI metrics on hand-made maps whose scores are known by construction.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/depth/metrics.h"

namespace lfsp::depth {
namespace {

// 40x40 maps: the evaluated interior (15 px frame ignored) is the 10x10 block [15, 25) x [15, 25).
// Interior errors, row-major over the 100 pixels: 10 x 0.1, 20 x 0.05, 30 x 0.02, 40 x 0.005.
void MakeKnownPair(DisparityMap& algo, DisparityMap& gt) {
  gt = DisparityMap(40, 40, 1.0f);
  algo = DisparityMap(40, 40, 1.0f);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      const bool inside = x >= 15 && x < 25 && y >= 15 && y < 25;
      if (!inside) {
        algo.at(y, x) = 100.0f;  // huge errors in the ignored frame must not count
        continue;
      }
      const int i = (y - 15) * 10 + (x - 15);
      const float error = i < 10 ? 0.1f : i < 30 ? 0.05f : i < 60 ? 0.02f : 0.005f;
      algo.at(y, x) = 1.0f + ((i % 2) ? error : -error);  // sign must not matter
    }
  }
}

TEST(DepthMetrics, KnownErrorsGiveTheHandComputedScores) {
  DisparityMap algo;
  DisparityMap gt;
  MakeKnownPair(algo, gt);
  const cv::Mat everything(40, 40, CV_8U, cv::Scalar(255));
  const DepthMetrics m = ComputeMetrics(algo, gt, everything);
  EXPECT_EQ(m.pixels, 100u);
  // MSE x100 = 100 * (10*0.01 + 20*0.0025 + 30*0.0004 + 40*0.000025) / 100 = 0.163
  EXPECT_NEAR(m.mse_x100, 0.163, 1e-4);
  EXPECT_NEAR(m.badpix_007, 10.0, 1e-9);
  EXPECT_NEAR(m.badpix_003, 30.0, 1e-9);
  EXPECT_NEAR(m.badpix_001, 60.0, 1e-9);
  // Sorted 100*|error|: 40 x 0.5 first, so element int(100 * 25 / 100) = 25 is 0.5.
  EXPECT_NEAR(m.q25, 0.5, 1e-4);
}

TEST(DepthMetrics, NonFiniteValuesFollowTheToolkit) {
  DisparityMap algo;
  DisparityMap gt;
  MakeKnownPair(algo, gt);
  // Two of the 0.1-error pixels become NaN / +inf: NaN is never "bad" but stays in the BadPix denominator, inf is
  // bad; both leave MSE and Q25.
  algo.at(15, 15) = std::numeric_limits<float>::quiet_NaN();
  algo.at(15, 16) = std::numeric_limits<float>::infinity();
  const cv::Mat everything(40, 40, CV_8U, cv::Scalar(255));
  const DepthMetrics m = ComputeMetrics(algo, gt, everything);
  EXPECT_EQ(m.pixels, 100u);
  EXPECT_NEAR(m.badpix_007, 9.0, 1e-9);  // 8 finite bad + inf
  EXPECT_NEAR(m.mse_x100, 100.0 * (8 * 0.01 + 20 * 0.0025 + 30 * 0.0004 + 40 * 0.000025) / 98.0, 1e-4);
  EXPECT_NEAR(m.q25, 0.5, 1e-4);
}

TEST(DepthMetrics, DiscontinuityRegionIsTheBandAroundAStep) {
  // A vertical step between columns 19 and 20: both are edge pixels; within 5 px: columns 14..25 (12 columns).
  DisparityMap gt(40, 30, 0.0f);
  for (int y = 0; y < 30; ++y) {
    for (int x = 20; x < 40; ++x) gt.at(y, x) = 1.0f;
  }
  const cv::Mat region = DiscontinuityRegion(gt, 0.1, 5.0);
  EXPECT_EQ(cv::countNonZero(region), 12 * 30);
  EXPECT_EQ(region.at<unsigned char>(10, 14), 255);
  EXPECT_EQ(region.at<unsigned char>(10, 25), 255);
  EXPECT_EQ(region.at<unsigned char>(10, 13), 0);
  EXPECT_EQ(region.at<unsigned char>(10, 26), 0);
  // A gentle slope (0.05 per pixel) is not a discontinuity.
  DisparityMap ramp(40, 30, 0.0f);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) ramp.at(y, x) = 0.05f * static_cast<float>(x);
  }
  EXPECT_EQ(cv::countNonZero(DiscontinuityRegion(ramp, 0.1, 5.0)), 0);
}

TEST(DepthMetrics, EvaluationSplitsAllAndNearDiscontinuities) {
  // 64x64, step at x = 32; errors of 0.2 only at the columns next to the step.
  DisparityMap gt(64, 64, 0.0f);
  for (int y = 0; y < 64; ++y) {
    for (int x = 32; x < 64; ++x) gt.at(y, x) = 2.0f;
  }
  DisparityMap algo = gt;
  for (int y = 0; y < 64; ++y) {
    algo.at(y, 31) += 0.2f;
    algo.at(y, 32) -= 0.2f;
  }
  const DepthEvaluation e = EvaluateDisparity(algo, gt);
  const double interior = 34.0 * 34.0;
  EXPECT_EQ(e.all.pixels, static_cast<std::size_t>(interior));
  EXPECT_NEAR(e.all.badpix_007, 100.0 * 2 * 34 / interior, 1e-9);
  EXPECT_EQ(e.near_discontinuities.pixels, 12u * 34u);  // columns 26..37 inside rows 15..48
  EXPECT_NEAR(e.near_discontinuities.badpix_007, 100.0 * 2.0 / 12.0, 1e-9);
  EXPECT_NEAR(e.near_discontinuities.mse_x100, 100.0 * 0.04 * 2.0 / 12.0, 1e-4);
}

TEST(DepthMetrics, SizeMismatchIsAnError) {
  const DisparityMap a(32, 32);
  const DisparityMap b(32, 31);
  EXPECT_THROW(EvaluateDisparity(a, b), Error);
  EXPECT_THROW(EvaluateDisparity(DisparityMap(), b), Error);
  EXPECT_THROW(ComputeMetrics(a, a, cv::Mat(10, 10, CV_8U)), Error);
}

}  // namespace
}  // namespace lfsp::depth
