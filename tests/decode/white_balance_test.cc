// The automatic white balance's search for grey surfaces (lfsp/decode/white_balance.h), on sensor images built so
// that which pixels are grey, and under which gains, is known.

#include "lfsp/decode/white_balance.h"

#include <gtest/gtest.h>

#include <array>
#include <opencv2/core.hpp>

#include "test_support.h"

namespace lfsp::decode {
namespace {

using lfsp::testing::ErrorOf;

const std::array<double, 9> kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1};

// A 200 x 200 sensor image of green foliage (G three times R) with a patch of grey surfaces covering `grey_share`
// of it, whose blue reads `blue_deficit` times too low (a light bluer or redder than the start gains were made for).
// One pixel is brighter than all others, so that the clip level sits above the scene.
cv::Mat Foliage(double grey_share, double blue_deficit) {
  cv::Mat rgb(200, 200, CV_32FC3, cv::Scalar(0.2, 0.6, 0.25));
  const int grey_rows = static_cast<int>(grey_share * 200.0 + 0.5);
  rgb(cv::Rect(0, 100, 200, grey_rows)).setTo(cv::Scalar(0.5, 0.5, 0.5 / blue_deficit));
  rgb.at<cv::Vec3f>(0, 0) = cv::Vec3f(1.0f, 1.0f, 1.0f);
  return rgb;
}

const cv::Mat kLit(200, 200, CV_32FC1, cv::Scalar(1.0));

// The search from gains 1, 1, 1 on Foliage(0.05, blue_deficit): the grey surfaces end grey (blue gain = the
// deficit), found from the tolerance `start_ratio`.
void ExpectGreySurfacesFound(double blue_deficit, double start_ratio) {
  AutoWhiteBalanceReport report;
  const auto gains = EstimateWhiteBalance(Foliage(0.05, blue_deficit), kLit, kIdentity, {1, 1, 1}, &report);
  EXPECT_NEAR(gains[0], 1.0, 1e-6);
  EXPECT_NEAR(gains[2], blue_deficit, 1e-6);
  EXPECT_DOUBLE_EQ(report.start_grey_ratio, start_ratio);
  EXPECT_DOUBLE_EQ(report.settled_grey_ratio, 1.3);
  EXPECT_FALSE(report.kept_start);
  // Settled at the strict tolerance: the grey patch alone votes, the foliage stays green.
  EXPECT_GT(report.grey_fraction, 0.04);
  EXPECT_LT(report.grey_fraction, 0.06);
}

TEST(AutoWhiteBalance, GreySurfacesWithinTheStrictToleranceDecideAlone) { ExpectGreySurfacesFound(1.2, 1.3); }

// Under the start gains the grey surfaces read 45 % bluish-short, beyond the strict tolerance (1.3), and nothing
// else is near grey: the search starts at the looser 1.6, then settles at the strict one. It kept the start gains
// before (the real IMG_3 under the F01's gains: 0.12 % grey).
TEST(AutoWhiteBalance, ALightFarFromTheStartGainsIsFoundThroughALooserTolerance) { ExpectGreySurfacesFound(1.45, 1.6); }

// Two surfaces, one 40 % reddish and one 40 % bluish, average to grey: the looser tolerance takes both and balances
// them, and at the strict one neither is grey under any gains. The looser tolerance's gains stand.
TEST(AutoWhiteBalance, GainsStayAtTheLooserToleranceWhenTheStrictOneFindsNone) {
  cv::Mat rgb = Foliage(0.0, 1.0);
  rgb(cv::Rect(0, 100, 200, 6)).setTo(cv::Scalar(0.7, 0.5, 0.5));  // the search reads every other row and column
  rgb(cv::Rect(0, 106, 200, 6)).setTo(cv::Scalar(0.5, 0.5, 0.7));
  AutoWhiteBalanceReport report;
  const auto gains = EstimateWhiteBalance(rgb, kLit, kIdentity, {1, 1, 1}, &report);
  EXPECT_NEAR(gains[0], 1.0 / 1.2, 1e-6);
  EXPECT_NEAR(gains[2], 1.0 / 1.2, 1e-6);
  EXPECT_DOUBLE_EQ(report.start_grey_ratio, 1.6);
  EXPECT_DOUBLE_EQ(report.settled_grey_ratio, 1.6);
  EXPECT_FALSE(report.kept_start);
  EXPECT_GT(report.grey_fraction, 0.04);
}

TEST(AutoWhiteBalance, ASceneWithoutGreyKeepsTheStartGains) {
  AutoWhiteBalanceReport report;
  const std::array<double, 3> start = {0.9, 1.0, 1.5};
  const auto gains = EstimateWhiteBalance(Foliage(0.0, 1.0), kLit, kIdentity, start, &report);
  EXPECT_EQ(gains, start);
  EXPECT_TRUE(report.kept_start);
  EXPECT_DOUBLE_EQ(report.start_grey_ratio, 2.0);  // every tolerance tried
  EXPECT_DOUBLE_EQ(report.settled_grey_ratio, 0.0);
  EXPECT_LT(report.grey_fraction, 0.002);
}

// The same estimate on a Bayer mosaic before any decoding: Foliage(0.05, 1.2) laid out as BGGR over a black level of
// 10, in micro-images 10 tiles apart whose dark gaps are near grey under other gains (red 1.2 times green, blue as
// the patch's): the lit tiles find the grey patch; were the gaps to vote, the red gain would fall towards 1 / 1.2.
TEST(AutoWhiteBalance, AMosaicsGreySurfacesAreFoundBeforeDecoding) {
  const cv::Mat rgb = Foliage(0.05, 1.2);
  cv::Mat mosaic(400, 400, CV_32FC1);
  for (int y = 0; y < 400; ++y)
    for (int x = 0; x < 400; ++x) {
      const cv::Vec3f& pixel = rgb.at<cv::Vec3f>(y / 2, x / 2);
      const int colour = (y & 1) == 0 ? ((x & 1) == 0 ? 2 : 1) : ((x & 1) == 0 ? 1 : 0);  // BGGR
      const int dx = (x / 2) % 10 - 5, dy = (y / 2) % 10 - 5;
      const bool lit = dx * dx + dy * dy <= 9;
      const float gap[3] = {0.12f, 0.1f, 0.1f / 1.2f};
      mosaic.at<float>(y, x) = 10.0f + 200.0f * (lit ? pixel[colour] : gap[colour]);
    }
  AutoWhiteBalanceReport report;
  const auto gains = EstimateMosaicWhiteBalance(mosaic, BayerPattern::kBGGR, 10.0, kIdentity, {1, 1, 1}, &report);
  EXPECT_NEAR(gains[0], 1.0, 1e-4);
  EXPECT_NEAR(gains[2], 1.2, 1e-4);
  EXPECT_FALSE(report.kept_start);
  EXPECT_NE(ErrorOf([] {
              (void)EstimateMosaicWhiteBalance(cv::Mat(1, 8, CV_32FC1), BayerPattern::kBGGR, 0.0, kIdentity, {1, 1, 1});
            }).find("need a float Bayer mosaic"),
            std::string::npos);
}

TEST(AutoWhiteBalance, ColourGainsGoToTheirBayerPhases) {
  const std::array<double, 3> gains = {1.25, 1.0, 1.5};
  EXPECT_EQ(BayerPhaseGains(BayerPattern::kBGGR, gains), (std::array<float, 4>{1.5f, 1.0f, 1.0f, 1.25f}));
  EXPECT_EQ(BayerPhaseGains(BayerPattern::kRGGB, gains), (std::array<float, 4>{1.25f, 1.0f, 1.0f, 1.5f}));
  EXPECT_EQ(BayerPhaseGains(BayerPattern::kGRBG, gains), (std::array<float, 4>{1.0f, 1.25f, 1.5f, 1.0f}));
  EXPECT_EQ(BayerPhaseGains(BayerPattern::kGBRG, gains), (std::array<float, 4>{1.0f, 1.5f, 1.25f, 1.0f}));
}

}  // namespace
}  // namespace lfsp::decode
