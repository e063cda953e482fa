#include <gtest/gtest.h>

#include <cmath>

#include "lfsp/core/visualize.h"

namespace lfsp {
namespace {

TEST(Visualize, EpisSliceTheRightSamples) {
  LightField light_field({3, 2, 4, 5, 3});
  for (int v = 0; v < 2; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 4; ++x)
          light_field.at({u, v}, y, x, 1) = static_cast<float>(1000 * v + 100 * u + 10 * y + x);
  const cv::Mat horizontal = HorizontalEpi(light_field, 3, 1);
  ASSERT_EQ(horizontal.rows, 3);
  ASSERT_EQ(horizontal.cols, 4);
  EXPECT_EQ(horizontal.at<cv::Vec3f>(2, 1)[1], 1000.0f + 200.0f + 30.0f + 1.0f);
  const cv::Mat vertical = VerticalEpi(light_field, 2, 1);
  ASSERT_EQ(vertical.rows, 5);
  ASSERT_EQ(vertical.cols, 2);
  EXPECT_EQ(vertical.at<cv::Vec3f>(4, 1)[1], 1000.0f + 100.0f + 40.0f + 2.0f);

  Labels labels(light_field.shape(), 7);
  labels.at({2, 0}, 4, 3) = 9;
  EXPECT_EQ(HorizontalEpi(labels, 4, 0).at<int>(2, 3), 9);
  EXPECT_EQ(VerticalEpi(labels, 3, 2).at<int>(4, 0), 9);
}

TEST(Visualize, BoundariesMarkOnlyLabelChanges) {
  cv::Mat labels(4, 6, CV_32SC1, cv::Scalar(1));
  labels.colRange(3, 6).setTo(2);
  const cv::Mat drawn = DrawLabelBoundaries(cv::Mat(4, 6, CV_8UC3, cv::Scalar::all(0)), labels, {255, 0, 0});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) EXPECT_EQ(drawn.at<cv::Vec3b>(y, x)[0], x == 2 ? 255 : 0) << x << "," << y;
}

TEST(Visualize, DisparityColourMapSpansTheRangeAndBlacksOutInvalid) {
  DisparityMap disparity(3, 1);
  disparity.at(0, 0) = -1.0f;
  disparity.at(0, 1) = 1.0f;
  disparity.at(0, 2) = std::nanf("");
  const cv::Mat rgb = ColourMapDisparity(disparity);
  EXPECT_NE(rgb.at<cv::Vec3b>(0, 0), rgb.at<cv::Vec3b>(0, 1));
  EXPECT_EQ(rgb.at<cv::Vec3b>(0, 2), cv::Vec3b(0, 0, 0));
}

TEST(Visualize, LinearDataIsSrgbEncodedForDisplay) {
  cv::Mat view(1, 1, CV_32FC3, cv::Scalar::all(0.2140));  // linear 0.214 ~ sRGB 0.5
  EXPECT_NEAR(DisplayRgb8(view, Transfer::kLinear).at<cv::Vec3b>(0, 0)[0], 128, 1);
  EXPECT_NEAR(DisplayRgb8(view, Transfer::kSrgb).at<cv::Vec3b>(0, 0)[0], 55, 1);
}

}  // namespace
}  // namespace lfsp
