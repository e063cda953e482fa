// The benchmark's region metrics (issue 43): bumpiness against hand-computed Hessians, the fattening index, the
// sparsification curve, and the evaluation masks, derived and read from a scene's files.

#include "lfsp/depth/region_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <opencv2/imgcodecs.hpp>

#include "lfsp/core/error.h"
#include "test_support.h"

namespace lfsp::depth {
namespace {

DisparityMap MapOf(int size, const std::function<float(int, int)>& value) {
  DisparityMap map(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) map.at(y, x) = value(y, x);
  return map;
}

cv::Mat Everything(int size) { return cv::Mat(size, size, CV_8U, cv::Scalar(255)); }

// An error of a x^2 / 2 has d2/dx2 = a and no other second derivative: |H|_F = a, and the score is 100 a.
TEST(Bumpiness, QuadraticErrorScoresItsCurvature) {
  const DisparityMap gt = MapOf(64, [](int y, int x) { return 0.3f + 0.01f * static_cast<float>(x + y); });
  const DisparityMap algo = MapOf(64, [&](int y, int x) {
    const double dx = x - 32.0;
    return gt.at(y, x) + static_cast<float>(0.02 * dx * dx / 2.0);
  });
  EXPECT_NEAR(Bumpiness(algo, gt, Everything(64)), 2.0, 1e-3);
}

// An error of c x y has d2/dxdy = d2/dydx = c: |H|_F = sqrt(2) c.
TEST(Bumpiness, SaddleErrorScoresBothMixedDerivatives) {
  const DisparityMap gt(64, 64, 1.0f);
  const DisparityMap algo =
      MapOf(64, [](int y, int x) { return 1.0f + static_cast<float>(0.01 * (x - 32) * (y - 32)); });
  EXPECT_NEAR(Bumpiness(algo, gt, Everything(64)), 100.0 * std::sqrt(2.0) * 0.01, 1e-3);
}

TEST(Bumpiness, ClipsAtFivePercentAndIgnoresPlanesAndOffsets) {
  const DisparityMap gt(64, 64, 0.0f);
  const DisparityMap steep = MapOf(64, [](int, int x) { return static_cast<float>(0.5 * (x - 32) * (x - 32) / 2.0); });
  EXPECT_NEAR(Bumpiness(steep, gt, Everything(64)), 5.0, 1e-9);
  const DisparityMap tilted = MapOf(64, [](int y, int x) { return 0.7f + 0.03f * static_cast<float>(x - 2 * y); });
  EXPECT_NEAR(Bumpiness(tilted, gt, Everything(64)), 0.0, 1e-4);
}

TEST(Bumpiness, EmptyRegionIsNotANumber) {
  const DisparityMap map(64, 64, 0.0f);
  EXPECT_TRUE(std::isnan(Bumpiness(map, map, cv::Mat(64, 64, CV_8U, cv::Scalar(0)))));
}

TEST(FatteningIndex, ShareOfBadPixelsThatReadNearer) {
  const DisparityMap gt(40, 40, 0.0f);
  DisparityMap algo(40, 40, 0.05f);  // off, but not bad at 0.07
  algo.at(20, 20) = 0.1f;            // nearer
  algo.at(20, 21) = 0.2f;            // nearer
  algo.at(21, 20) = 0.3f;            // nearer
  algo.at(21, 21) = -0.1f;           // farther
  algo.at(2, 2) = 1.0f;              // nearer, but in the ignored frame
  EXPECT_DOUBLE_EQ(FatteningIndex(algo, gt, Everything(40)), 75.0);
  EXPECT_TRUE(std::isnan(FatteningIndex(gt, gt, Everything(40))));
}

TEST(Sparsification, PerfectConfidenceMatchesTheOracle) {
  const DisparityMap gt(40, 40, 0.0f);
  const DisparityMap algo = MapOf(40, [](int y, int x) { return 0.01f * static_cast<float>((x * 7 + y * 3) % 17); });
  const DisparityMap perfect = MapOf(40, [&](int y, int x) { return -std::abs(algo.at(y, x)); });
  const Sparsification s = SparsificationOf(algo, gt, perfect);
  ASSERT_EQ(s.curve.size(), 100u);
  EXPECT_NEAR(s.area_between, 0.0, 1e-12);
  // All pixels: the MSE x100 of the whole frame, for any order.
  EXPECT_NEAR(s.curve.back(), EvaluateDisparity(algo, gt).all.mse_x100, 1e-9);
  EXPECT_NEAR(s.oracle.back(), s.curve.back(), 1e-12);
  // The oracle keeps the smallest errors first: its curve never falls.
  for (std::size_t i = 1; i < s.oracle.size(); ++i) EXPECT_GE(s.oracle[i], s.oracle[i - 1] - 1e-12);

  const DisparityMap backwards = MapOf(40, [&](int y, int x) { return std::abs(algo.at(y, x)); });
  const Sparsification worst = SparsificationOf(algo, gt, backwards);
  EXPECT_GT(worst.area_between, 0.5 * worst.area);
}

TEST(Sparsification, ConfidenceOfAnotherSizeIsRefused) {
  const DisparityMap map(40, 40, 0.0f);
  EXPECT_NE(testing::ErrorOf([&] { SparsificationOf(map, map, DisparityMap(20, 40)); }).find("confidence map"),
            std::string::npos);
}

// A plane on the left, a curved bump on the right, a step between them.
DisparityMap PlaneStepBump() {
  return MapOf(96, [](int y, int x) {
    if (x < 48) return 0.5f + 0.01f * static_cast<float>(x) - 0.005f * static_cast<float>(y);
    const double dx = x - 72.0, dy = y - 48.0;
    return static_cast<float>(1.5 - 0.0005 * (dx * dx + dy * dy));
  });
}

TEST(EvaluationMasks, DerivedRegionsSeparatePlanesCurvesAndSteps) {
  const DisparityMap gt = PlaneStepBump();
  const EvaluationMasks masks = DeriveEvaluationMasks(gt, MetricOptions{});
  EXPECT_EQ(masks.planes.at<unsigned char>(48, 20), 255);
  EXPECT_EQ(masks.smooth_surfaces.at<unsigned char>(48, 20), 0);
  EXPECT_EQ(masks.smooth_surfaces.at<unsigned char>(48, 72), 255);
  EXPECT_EQ(masks.planes.at<unsigned char>(48, 72), 0);
  EXPECT_EQ(masks.discontinuities.at<unsigned char>(48, 48), 255);
  EXPECT_EQ(masks.planes.at<unsigned char>(48, 46), 0);
  EXPECT_EQ(masks.smooth_surfaces.at<unsigned char>(48, 50), 0);
  EXPECT_EQ(cv::countNonZero(masks.planes & masks.smooth_surfaces), 0);
  EXPECT_EQ(cv::countNonZero(masks.planes & masks.discontinuities), 0);
  EXPECT_EQ(masks.planes_source, "derived from the ground truth");
}

TEST(EvaluationMasks, SceneFilesWinAndHighResolutionMasksAreReduced) {
  const DisparityMap gt = PlaneStepBump();
  const testing::TempDir folder;
  cv::Mat discontinuities(192, 192, CV_8U, cv::Scalar(0));
  discontinuities.at<unsigned char>(11, 21) = 255;  // one high-resolution pixel: low-resolution (5, 10) is near
  cv::imwrite((folder / "mask_discontinuities.png").string(), discontinuities);
  cv::Mat planes(192, 192, CV_8U, cv::Scalar(255));
  planes.at<unsigned char>(40, 40) = 0;  // low-resolution (20, 20) is no longer all plane
  cv::imwrite((folder / "mask_planes.png").string(), planes);
  const EvaluationMasks masks = ReadEvaluationMasks(folder.path(), gt, MetricOptions{});
  EXPECT_EQ(cv::countNonZero(masks.discontinuities), 1);
  EXPECT_EQ(masks.discontinuities.at<unsigned char>(5, 10), 255);
  EXPECT_EQ(cv::countNonZero(masks.planes), 96 * 96 - 1);
  EXPECT_EQ(masks.planes.at<unsigned char>(20, 20), 0);
  EXPECT_NE(masks.planes_source.find("mask_planes.png"), std::string::npos);
  EXPECT_EQ(masks.smooth_surfaces_source, "derived from the ground truth");

  cv::imwrite((folder / "mask_smooth_surfaces.png").string(), cv::Mat(100, 96, CV_8U, cv::Scalar(255)));
  const std::string error = testing::ErrorOf([&] { ReadEvaluationMasks(folder.path(), gt, MetricOptions{}); });
  EXPECT_NE(error.find("mask_smooth_surfaces.png"), std::string::npos) << error;
  EXPECT_NE(error.find("96x100"), std::string::npos) << error;
}

TEST(EvaluateDisparity, ReportsEveryRegionFigure) {
  const DisparityMap gt = PlaneStepBump();
  DisparityMap algo = gt;
  for (int y = 0; y < 96; ++y)
    for (int x = 44; x < 48; ++x) algo.at(y, x) = gt.at(y, x) + 0.3f;  // read nearer beside the step
  const DepthEvaluation evaluation = EvaluateDisparity(algo, gt);
  EXPECT_GT(evaluation.near_discontinuities.badpix_007, 0.0);
  EXPECT_DOUBLE_EQ(evaluation.fattening_all, 100.0);
  EXPECT_GT(evaluation.plane_pixels, 0u);
  EXPECT_GT(evaluation.smooth_surface_pixels, 0u);
  EXPECT_NEAR(evaluation.bumpiness_smooth_surfaces, 0.0, 1e-6);
  const nlohmann::json json = ToJson(evaluation);
  EXPECT_EQ(json["fattening_index"]["all"], 100.0);
  EXPECT_TRUE(json["bumpiness"].contains("planes"));
  EXPECT_FALSE(json.contains("sparsification"));
}

}  // namespace
}  // namespace lfsp::depth
