// Unit tests of segment/src/planes.h (issue 14 item 5): FitPlanes, the per-superpixel robust plane fit of the
// centre-view disparity, and SmoothPlanes, the boundary typing (occlusion / hinge / coplanar) and coupled re-fit of
// Eq. 5. Every input is a small hand-built label map whose right answer follows in closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

#include "lfsp/segment/params.h"
#include "lfsp/segment/plane.h"
#include "planes.h"

namespace lfsp::segment {
namespace {

constexpr double kTolerance = 1e-4;  // float disparity samples, double solve

cv::Mat LabelMap(int width, int height, int fill = 0) { return cv::Mat(height, width, CV_32SC1, cv::Scalar(fill)); }

// Disparity of the plane d = a x + b y + c sampled at every pixel.
cv::Mat PlaneDisparity(int width, int height, const Plane& plane) {
  cv::Mat d(height, width, CV_32FC1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) d.at<float>(y, x) = static_cast<float>(plane.AtCentre(x, y));
  return d;
}

// Left columns [0, split) label 0, the rest label 1.
cv::Mat TwoColumns(int width, int height, int split) {
  cv::Mat labels = LabelMap(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = split; x < width; ++x) labels.at<int>(y, x) = 1;
  return labels;
}

void ExpectPlane(const Plane& actual, const Plane& expected, double tolerance = kTolerance) {
  EXPECT_NEAR(actual.a, expected.a, tolerance);
  EXPECT_NEAR(actual.b, expected.b, tolerance);
  EXPECT_NEAR(actual.c, expected.c, tolerance);
}

// --- FitPlanes ---

TEST(FitPlanes, RecoversAnExactSlantedPlane) {
  const Plane truth{0.05, -0.02, 1.5};
  const std::vector<Plane> planes = FitPlanes(LabelMap(12, 9), 1, PlaneDisparity(12, 9, truth), 0.5);
  ASSERT_EQ(planes.size(), 1u);
  ExpectPlane(planes[0], truth);
}

TEST(FitPlanes, RecoversASteepPlaneWhoseSamplesMostlyStartAsOutliers) {
  // The fit starts fronto-parallel at the median; with slope 0.3 px/px only the middle columns are within the
  // 0.5 threshold of it, and the re-fits on the inliers must still reach the whole plane.
  const Plane truth{0.3, 0.1, -2.0};
  const std::vector<Plane> planes = FitPlanes(LabelMap(16, 8), 1, PlaneDisparity(16, 8, truth), 0.5);
  ExpectPlane(planes[0], truth);
}

TEST(FitPlanes, FitsEachLabelToItsOwnPixelsOnly) {
  // Label 0 on the left 5 columns lies on one plane, label 1 on the right 5 on another (a step at the boundary).
  const Plane left{0.02, 0.01, 0.5}, right{-0.03, 0.02, 2.0};
  const cv::Mat labels = TwoColumns(10, 8, 5);
  cv::Mat d = PlaneDisparity(10, 8, left);
  PlaneDisparity(10, 8, right).copyTo(d, labels == 1);
  const std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  ASSERT_EQ(planes.size(), 2u);
  ExpectPlane(planes[0], left);
  ExpectPlane(planes[1], right);
}

TEST(FitPlanes, OutliersAboveTheInlierThresholdDoNotPullThePlane) {
  const Plane truth{0.02, 0.01, 1.0};  // spans 0.27 over 10x10: every true sample is within 0.5 of the median
  cv::Mat d = PlaneDisparity(10, 10, truth);
  for (int i = 0; i < 8; ++i) d.at<float>(i, (3 * i) % 10) += 3.0f;  // 8 of 100 samples 3 px too near
  const std::vector<Plane> robust = FitPlanes(LabelMap(10, 10), 1, d, 0.5);
  ExpectPlane(robust[0], truth);
  // The same samples with a threshold that admits the outliers: they do pull the fit (so the test above can fail).
  const std::vector<Plane> plain = FitPlanes(LabelMap(10, 10), 1, d, 100.0);
  EXPECT_GT(std::abs(plain[0].AtCentre(4.5, 4.5) - truth.AtCentre(4.5, 4.5)), 0.1);
}

TEST(FitPlanes, NonFiniteSamplesAreIgnored) {
  const Plane truth{-0.04, 0.03, 0.75};
  cv::Mat d = PlaneDisparity(8, 8, truth);
  d.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
  d.at<float>(3, 5) = std::numeric_limits<float>::infinity();
  d.at<float>(7, 2) = -std::numeric_limits<float>::infinity();
  const std::vector<Plane> planes = FitPlanes(LabelMap(8, 8), 1, d, 0.5);
  ExpectPlane(planes[0], truth);
}

TEST(FitPlanes, OnePixelLabelGetsAFrontoParallelPlaneAtItsDisparity) {
  cv::Mat labels = LabelMap(6, 5);
  labels.at<int>(2, 3) = 1;  // label 1 is the single pixel (3, 2)
  cv::Mat d = PlaneDisparity(6, 5, {0.01, 0.02, 0.0});
  d.at<float>(2, 3) = 2.25f;
  const std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  ExpectPlane(planes[1], {0.0, 0.0, 2.25}, 1e-12);
}

TEST(FitPlanes, TwoPixelLabelGetsAFrontoParallelPlane) {
  cv::Mat labels = LabelMap(6, 5);
  labels.at<int>(1, 1) = 1;
  labels.at<int>(2, 2) = 1;
  cv::Mat d(5, 6, CV_32FC1, cv::Scalar(0.0f));
  d.at<float>(1, 1) = -1.5f;
  d.at<float>(2, 2) = -1.5f;
  const std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  ExpectPlane(planes[1], {0.0, 0.0, -1.5}, 1e-12);
}

TEST(FitPlanes, CollinearSupportGetsAFrontoParallelPlaneAtTheMedian) {
  // Label 1 is the single row y = 2, x = 0..4, with d = 1.0, 1.1, ..., 1.4: the slope across the row is undefined,
  // so the plane is fronto-parallel at the median 1.2, not a fit of the row's slope 0.1.
  cv::Mat labels = LabelMap(5, 5);
  cv::Mat d(5, 5, CV_32FC1, cv::Scalar(0.0f));
  for (int x = 0; x < 5; ++x) {
    labels.at<int>(2, x) = 1;
    d.at<float>(2, x) = 1.0f + 0.1f * static_cast<float>(x);
  }
  const std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  ExpectPlane(planes[1], {0.0, 0.0, 1.2}, 1e-6);
}

TEST(FitPlanes, DiagonalCollinearSupportIsDegenerateToo) {
  cv::Mat labels = LabelMap(6, 6);
  cv::Mat d(6, 6, CV_32FC1, cv::Scalar(0.0f));
  for (int i = 0; i < 5; ++i) {
    labels.at<int>(i, i) = 1;
    d.at<float>(i, i) = 0.5f + 0.2f * static_cast<float>(i);  // 0.5 .. 1.3, median 0.9
  }
  const std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  ExpectPlane(planes[1], {0.0, 0.0, 0.9}, 1e-6);
}

TEST(FitPlanes, LabelWithoutPixelsGetsAFinitePlane) {
  const std::vector<Plane> planes = FitPlanes(LabelMap(4, 4), 3, PlaneDisparity(4, 4, {0.1, 0.1, 1.0}), 0.5);
  ASSERT_EQ(planes.size(), 3u);
  ExpectPlane(planes[0], {0.1, 0.1, 1.0});
  for (int k = 1; k < 3; ++k) {
    EXPECT_EQ(planes[static_cast<std::size_t>(k)].a, 0.0);
    EXPECT_EQ(planes[static_cast<std::size_t>(k)].b, 0.0);
    EXPECT_TRUE(std::isfinite(planes[static_cast<std::size_t>(k)].c));
  }
}

// --- SmoothPlanes ---

LfspParams SmoothingParams(double lambda_s) {
  LfspParams params;
  params.lambda_s = lambda_s;
  params.lambda_d = 50.0;
  params.plane_iterations = 10;
  return params;
}

TEST(SmoothPlanes, CoplanarNeighboursAreTypedCoplanarAndKeepTheirCommonPlane) {
  const Plane truth{0.03, -0.01, 1.0};
  const cv::Mat labels = TwoColumns(10, 6, 5);
  const cv::Mat d = PlaneDisparity(10, 6, truth);
  std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  const BoundaryTypeCounts counts = SmoothPlanes(labels, 2, d, 1.0, SmoothingParams(1.0), planes);
  EXPECT_EQ(counts.coplanar, 1);
  EXPECT_EQ(counts.hinge, 0);
  EXPECT_EQ(counts.occlusion, 0);
  ExpectPlane(planes[0], truth);
  ExpectPlane(planes[1], truth);
}

TEST(SmoothPlanes, ALargeStepIsAnOcclusionAndDoesNotCoupleThePlanes) {
  // d = 0 left, 3 right: occlusion costs 0.25, hinge 0.05 + 9, coplanar 9. Even a huge lambda_s must not pull the
  // planes together across an occlusion.
  const cv::Mat labels = TwoColumns(10, 6, 5);
  cv::Mat d(6, 10, CV_32FC1, cv::Scalar(0.0f));
  d.setTo(3.0f, labels == 1);
  std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  const BoundaryTypeCounts counts = SmoothPlanes(labels, 2, d, 3.0, SmoothingParams(1e4), planes);
  EXPECT_EQ(counts.occlusion, 1);
  EXPECT_EQ(counts.hinge + counts.coplanar, 0);
  ExpectPlane(planes[0], {0.0, 0.0, 0.0});
  ExpectPlane(planes[1], {0.0, 0.0, 3.0});
}

TEST(SmoothPlanes, AnExpensiveOcclusionTurnsTheStepCoplanar) {
  // The same step with occlusion_penalty 100: coplanar (mean squared difference 9) is now the cheapest type.
  const cv::Mat labels = TwoColumns(10, 6, 5);
  cv::Mat d(6, 10, CV_32FC1, cv::Scalar(0.0f));
  d.setTo(3.0f, labels == 1);
  std::vector<Plane> planes = FitPlanes(labels, 2, d, 0.5);
  LfspParams params = SmoothingParams(0.0);  // no coupling: the planes stay, only the typing changes
  params.occlusion_penalty = 100.0;
  const BoundaryTypeCounts counts = SmoothPlanes(labels, 2, d, 3.0, params, planes);
  EXPECT_EQ(counts.coplanar, 1);
  EXPECT_EQ(counts.occlusion + counts.hinge, 0);
}

// A roof: two planes of opposite slope meeting on the boundary between columns 4 and 5 (boundary samples at
// x = 4.5). Hinge costs 0.05 + 0 there; coplanar costs the mean of (0.2 (x - 4.5))^2 over all pixels = 0.33; an
// occlusion 0.25.
struct Roof {
  cv::Mat labels = TwoColumns(10, 6, 5);
  Plane left{0.1, 0.0, 1.0 - 0.45};
  Plane right{-0.1, 0.0, 1.0 + 0.45};
  cv::Mat disparity() const {
    cv::Mat d = PlaneDisparity(10, 6, left);
    PlaneDisparity(10, 6, right).copyTo(d, labels == 1);
    return d;
  }
};

TEST(SmoothPlanes, PlanesMeetingOnTheBoundaryAreAHinge) {
  const Roof roof;
  const cv::Mat d = roof.disparity();
  std::vector<Plane> planes = FitPlanes(roof.labels, 2, d, 0.5);
  ExpectPlane(planes[0], roof.left);
  ExpectPlane(planes[1], roof.right);
  const BoundaryTypeCounts counts = SmoothPlanes(roof.labels, 2, d, 1.0, SmoothingParams(1.0), planes);
  EXPECT_EQ(counts.hinge, 1);
  EXPECT_EQ(counts.occlusion + counts.coplanar, 0);
  // A hinge only asks the planes to agree on the boundary, which they already do: the exact fits stay.
  ExpectPlane(planes[0], roof.left);
  ExpectPlane(planes[1], roof.right);
}

TEST(SmoothPlanes, AnExpensiveHingeTurnsTheRoofIntoAnOcclusion) {
  const Roof roof;
  const cv::Mat d = roof.disparity();
  std::vector<Plane> planes = FitPlanes(roof.labels, 2, d, 0.5);
  LfspParams params = SmoothingParams(1.0);
  params.hinge_penalty = 1.0;  // hinge 1.0 > coplanar 0.33 > occlusion 0.25
  const BoundaryTypeCounts counts = SmoothPlanes(roof.labels, 2, d, 1.0, params, planes);
  EXPECT_EQ(counts.occlusion, 1);
  EXPECT_EQ(counts.hinge + counts.coplanar, 0);
  ExpectPlane(planes[0], roof.left);
  ExpectPlane(planes[1], roof.right);
}

// Two fronto-parallel halves 0.2 apart: coplanar (0.04) beats hinge (0.09) and occlusion (0.25).
struct SmallStep {
  cv::Mat labels = TwoColumns(10, 6, 5);
  cv::Mat disparity() const {
    cv::Mat d(6, 10, CV_32FC1, cv::Scalar(1.0f));
    d.setTo(1.2f, labels == 1);
    return d;
  }
};

TEST(SmoothPlanes, WithoutSmoothnessWeightThePlanesStayTheDataFits) {
  const SmallStep step;
  const cv::Mat d = step.disparity();
  std::vector<Plane> planes = FitPlanes(step.labels, 2, d, 0.5);
  const BoundaryTypeCounts counts = SmoothPlanes(step.labels, 2, d, 1.0, SmoothingParams(0.0), planes);
  EXPECT_EQ(counts.coplanar, 1);
  ExpectPlane(planes[0], {0.0, 0.0, 1.0});
  ExpectPlane(planes[1], {0.0, 0.0, 1.2});
}

double GapAtCentre(const std::vector<Plane>& planes) {
  // Mean over the 10x6 frame of plane 1 - plane 0 (planes are affine, so the value at the frame's centre).
  return planes[1].AtCentre(4.5, 2.5) - planes[0].AtCentre(4.5, 2.5);
}

TEST(SmoothPlanes, CoplanarCouplingPullsNeighbouringPlanesTogetherMoreAsLambdaSGrows) {
  const SmallStep step;
  const cv::Mat d = step.disparity();
  double previous_gap = 0.2 + 1e-9;
  for (double lambda_s : {0.01, 1.0, 100.0, 1e4}) {
    std::vector<Plane> planes = FitPlanes(step.labels, 2, d, 0.5);
    SmoothPlanes(step.labels, 2, d, 1.0, SmoothingParams(lambda_s), planes);
    const double gap = GapAtCentre(planes);
    EXPECT_GT(gap, 0.0) << "lambda_s " << lambda_s << ": the planes do not cross";
    EXPECT_LT(gap, previous_gap) << "lambda_s " << lambda_s;
    // Both move: plane 0 up from 1.0, plane 1 down from 1.2, and they stay between the data.
    EXPECT_GT(planes[0].AtCentre(4.5, 2.5), 1.0 - 1e-9) << "lambda_s " << lambda_s;
    EXPECT_LT(planes[1].AtCentre(4.5, 2.5), 1.2 + 1e-9) << "lambda_s " << lambda_s;
    previous_gap = gap;
  }
  // E_s is a mean over the boundary or the pair's pixels (Eq. 5) while E_d sums over pixels: 30 pixels of data weight
  // 50 give 1500 against lambda_s, so only lambda_s well above that nearly merges the planes (measured gap 0.0033).
  EXPECT_LT(previous_gap, 0.01);
}

TEST(SmoothPlanes, ATinyLambdaSAgainstTheDataWeightBarelyMovesThePlanes) {
  // Table II's lambda_s = 0.01 against lambda_d / range^2 = 50 per pixel: the planes keep to their data.
  const SmallStep step;
  const cv::Mat d = step.disparity();
  std::vector<Plane> planes = FitPlanes(step.labels, 2, d, 0.5);
  SmoothPlanes(step.labels, 2, d, 1.0, SmoothingParams(0.01), planes);
  EXPECT_NEAR(GapAtCentre(planes), 0.2, 1e-3);
}

TEST(SmoothPlanes, BoundariesAreBetweenFourNeighboursOnlyAndCountedOncePerPair) {
  // Four 4x4 quadrants 0 1 / 2 3: diagonal quadrants touch only at a corner, so there are 4 boundaries
  // (0-1, 0-2, 1-3, 2-3), all coplanar on one common plane.
  cv::Mat labels = LabelMap(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) labels.at<int>(y, x) = (y / 4) * 2 + x / 4;
  const Plane truth{0.01, 0.02, 0.5};
  const cv::Mat d = PlaneDisparity(8, 8, truth);
  std::vector<Plane> planes = FitPlanes(labels, 4, d, 0.5);
  const BoundaryTypeCounts counts = SmoothPlanes(labels, 4, d, 1.0, SmoothingParams(1.0), planes);
  EXPECT_EQ(counts.coplanar, 4);
  EXPECT_EQ(counts.hinge + counts.occlusion, 0);
  for (const Plane& plane : planes) ExpectPlane(plane, truth);
}

TEST(SmoothPlanes, ZeroPlaneIterationsOnlyTypesTheBoundaries) {
  const SmallStep step;
  const cv::Mat d = step.disparity();
  std::vector<Plane> planes = FitPlanes(step.labels, 2, d, 0.5);
  LfspParams params = SmoothingParams(100.0);
  params.plane_iterations = 0;
  const BoundaryTypeCounts counts = SmoothPlanes(step.labels, 2, d, 1.0, params, planes);
  EXPECT_EQ(counts.coplanar, 1);
  ExpectPlane(planes[0], {0.0, 0.0, 1.0});
  ExpectPlane(planes[1], {0.0, 0.0, 1.2});
}

}  // namespace
}  // namespace lfsp::segment
