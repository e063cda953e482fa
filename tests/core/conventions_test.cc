#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>

#include <opencv2/core.hpp>

#include "lfsp/core/conventions.h"
#include "lfsp/core/light_field.h"

namespace lfsp {
namespace {

TEST(Conventions, CameraNumbersAreRowMajorAsInHci) {
  EXPECT_EQ(CameraNumber({4, 4}, 9), 40);  // input_Cam040.png is the centre of 9x9
  EXPECT_EQ(CameraNumber({8, 0}, 9), 8);
  EXPECT_EQ(CameraNumber({0, 1}, 9), 9);
  EXPECT_EQ(ViewFromCameraNumber(40, 9), (ViewIndex{4, 4}));
  EXPECT_EQ(ViewFromCameraNumber(13, 5), (ViewIndex{3, 2}));
}

TEST(Conventions, CentreViewOfOddAndEvenGrids) {
  EXPECT_EQ(CentreView(9, 9), (ViewIndex{4, 4}));
  EXPECT_EQ(CentreView(15, 15), (ViewIndex{7, 7}));
  EXPECT_EQ(CentreView(14, 14), (ViewIndex{6, 6}));  // (nu-1)/2 rounds down
  EXPECT_EQ(CentreView(5, 3), (ViewIndex{2, 1}));
}

TEST(Conventions, CentrePixelMovesAgainstTheViewOffsetForPositiveDisparity) {
  const ViewIndex centre{4, 4};
  const PixelPosition p = ProjectFromCentre({100.0f, 50.0f}, 2.0f, {6, 3}, centre);
  EXPECT_FLOAT_EQ(p.x, 100.0f - 2 * 2.0f);
  EXPECT_FLOAT_EQ(p.y, 50.0f - (-1) * 2.0f);
  const PixelPosition same = ProjectFromCentre({10.0f, 20.0f}, 3.0f, centre, centre);
  EXPECT_FLOAT_EQ(same.x, 10.0f);
  EXPECT_FLOAT_EQ(same.y, 20.0f);
}

TEST(LightField, MemoryLayoutIsViewRowColumnChannel) {
  LightFieldShape shape{3, 2, 5, 4, 3};  // nu=3, nv=2, width=5, height=4
  LightField light_field(shape);
  EXPECT_EQ(light_field.size(), 3u * 2u * 5u * 4u * 3u);
  light_field.at({2, 1}, 3, 4, 2) = 7.0f;
  // [v][u][y][x][c]: ((v*nu + u)*H + y)*W*C + x*C + c
  const std::size_t offset = ((1 * 3 + 2) * 4 + 3) * 5 * 3 + 4 * 3 + 2;
  EXPECT_EQ(light_field.data()[offset], 7.0f);
}

TEST(LightField, ViewIsAZeroCopyMat) {
  LightField light_field({3, 3, 8, 6, 3});
  cv::Mat view = light_field.View({1, 2});
  EXPECT_EQ(view.cols, 8);
  EXPECT_EQ(view.rows, 6);
  EXPECT_EQ(view.type(), CV_32FC3);
  EXPECT_EQ(reinterpret_cast<float*>(view.data), light_field.ViewData({1, 2}));
  view.at<cv::Vec3f>(5, 7)[1] = 0.25f;
  EXPECT_EQ(light_field.at({1, 2}, 5, 7, 1), 0.25f);
}

TEST(LightField, WeightsAndLabelsShareTheLayoutWithOneChannel) {
  LightField light_field({3, 3, 8, 6, 3});
  EXPECT_FALSE(light_field.HasWeights());
  light_field.EnableWeights(0.5f);
  EXPECT_TRUE(light_field.HasWeights());
  EXPECT_EQ(light_field.weights().size(), 3u * 3u * 8u * 6u);
  light_field.WeightView({2, 0}).at<float>(1, 2) = 0.75f;
  EXPECT_EQ(light_field.weights().at({2, 0}, 1, 2), 0.75f);

  Labels labels(light_field.shape());
  EXPECT_EQ(labels.shape().channels, 1);
  EXPECT_EQ(labels.at({0, 0}, 0, 0), Labels::kUnlabelled);
  labels.View({1, 1}).at<int>(3, 4) = 12;
  EXPECT_EQ(labels.at({1, 1}, 3, 4), 12);
}

TEST(LightField, ArraysHoldTheirFillAndUnfilledOnesOnlySkipIt) {
  // Array4D keeps its samples in an UninitializedVector: sizing with a fill must still fill (a light field starts
  // black, labels unlabelled), and an Unfilled array has the same shape and size for a caller to write in full.
  const LightFieldShape shape{3, 3, 8, 6, 3};
  const LightField light_field(shape);
  EXPECT_TRUE(
      std::all_of(light_field.data(), light_field.data() + light_field.size(), [](float v) { return v == 0.0f; }));
  const Labels filled(shape, 7);
  EXPECT_TRUE(std::all_of(filled.data(), filled.data() + filled.size(), [](std::int32_t v) { return v == 7; }));
  Labels unfilled(shape, Labels::Unfilled{});
  EXPECT_EQ(unfilled.shape(), filled.shape());
  EXPECT_EQ(unfilled.size(), filled.size());
  unfilled.View({2, 2}).at<int>(7, 5) = 3;
  EXPECT_EQ(unfilled.at({2, 2}, 7, 5), 3);
}

TEST(DisparityMap, MatSharesMemory) {
  DisparityMap disparity(7, 3, 1.5f);
  disparity.Mat().at<float>(2, 6) = -2.0f;
  EXPECT_EQ(disparity.at(2, 6), -2.0f);
  EXPECT_EQ(disparity.at(0, 0), 1.5f);
}

}  // namespace
}  // namespace lfsp
