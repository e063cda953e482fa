// Unit tests of segment/src/centre_carry.h: LFSP's last step, which carries the refined centre labels into the side
// views along the disparity. Light fields of 3 x 1 views of 8 x 1 pixels: the centre view's two superpixels meet
// between x = 3 and x = 4, and (docs/DESIGN.md convention) a centre pixel x0 with disparity d lands at x0 - du d in
// the view at offset du.

#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "centre_carry.h"
#include "lfsp/core/light_field.h"
#include "lfsp/segment/plane.h"

namespace lfsp::segment {
namespace {

constexpr int kWidth = 8;

// Labels of three views in a row: left (du = -1), centre, right (du = +1).
Labels ThreeViews(const std::vector<std::int32_t>& left, const std::vector<std::int32_t>& centre,
                  const std::vector<std::int32_t>& right) {
  Labels labels(LightFieldShape{3, 1, kWidth, 1, 3});
  const std::vector<std::int32_t>* views[] = {&left, &centre, &right};
  for (int u = 0; u < 3; ++u) {
    std::int32_t* out = labels.ViewData(ViewIndex{u, 0});
    for (int x = 0; x < kWidth; ++x) out[x] = (*views[u])[static_cast<std::size_t>(x)];
  }
  return labels;
}

std::vector<std::int32_t> View(const Labels& labels, int u) {
  const std::int32_t* data = labels.ViewData(ViewIndex{u, 0});
  return {data, data + kWidth};
}

const std::vector<std::int32_t> kCentre{0, 0, 0, 0, 1, 1, 1, 1};

// Fronto-parallel planes of the two superpixels at these disparities.
std::vector<Plane> Planes(double left, double right) { return {Plane{0.0, 0.0, left}, Plane{0.0, 0.0, right}}; }

TEST(CentreCarry, SideViewsThatDriftedTakeTheCarriedLabels) {
  // Disparity 1: the right view sees centre pixel x0 at x0 - 1, the left one at x0 + 1. The side views' labels have
  // drifted to one superpixel each.
  Labels labels = ThreeViews(std::vector<std::int32_t>(kWidth, 0), kCentre, std::vector<std::int32_t>(kWidth, 1));
  CarryCentreToSideViews(cv::Mat(1, kWidth, CV_32F, cv::Scalar(1.0f)), Planes(1.0, 1.0), labels);
  EXPECT_EQ(View(labels, 1), kCentre) << "the centre view is never changed";
  // Right view: nothing lands on x = 7 (the centre does not see that ray), so it keeps its refined label.
  EXPECT_EQ(View(labels, 2), (std::vector<std::int32_t>{0, 0, 0, 1, 1, 1, 1, 1}));
  // Left view: x = 0 is the ray the centre does not see.
  EXPECT_EQ(View(labels, 0), (std::vector<std::int32_t>{0, 0, 0, 0, 0, 1, 1, 1}));
}

TEST(CentreCarry, ARefinedBoundaryOneRoundingAwayStays) {
  // Disparity 0.5: the right view's ray x images the centre at x + 0.5, between two centre pixels. Its carried label
  // is the rounded one's (x + 1 lands on x: ForwardWarp rounds x0 - 0.5 half up), so around the boundary either
  // label is as right as the other, and the refinement's stays. Two pixels off is a drift and is carried back.
  const cv::Mat disparity(1, kWidth, CV_32F, cv::Scalar(0.5f));
  Labels one_off = ThreeViews(kCentre, kCentre, {0, 0, 0, 1, 1, 1, 1, 1});
  CarryCentreToSideViews(disparity, Planes(0.5, 0.5), one_off);
  EXPECT_EQ(View(one_off, 2), (std::vector<std::int32_t>{0, 0, 0, 1, 1, 1, 1, 1}));

  Labels two_off = ThreeViews(kCentre, kCentre, {0, 0, 1, 1, 1, 1, 1, 1});
  CarryCentreToSideViews(disparity, Planes(0.5, 0.5), two_off);
  EXPECT_EQ(View(two_off, 2), (std::vector<std::int32_t>{0, 0, 0, 1, 1, 1, 1, 1}));
}

TEST(CentreCarry, AWholeShiftKeepsOnlyTheCarriedBoundary) {
  // Disparity 1 (a whole pixel): the ray's source position is a pixel, so no neighbouring label is "one rounding
  // away" and a boundary one pixel off is carried back.
  Labels labels = ThreeViews(kCentre, kCentre, {0, 0, 1, 1, 1, 1, 1, 1});
  CarryCentreToSideViews(cv::Mat(1, kWidth, CV_32F, cv::Scalar(1.0f)), Planes(1.0, 1.0), labels);
  EXPECT_EQ(View(labels, 2), (std::vector<std::int32_t>{0, 0, 0, 1, 1, 1, 1, 1}));
}

TEST(CentreCarry, AnOccludersEdgeARoundingAwayOnItsOwnSurfaceStays) {
  // Superpixel 0 in front (disparity 1.4), superpixel 1 behind (-0.4). In the left view (du = -1) centre pixel x0 of
  // 0 lands at x0 + 1 and of 1 at x0, so the carry gives [-, 0, 0, 0, 0, 1, 1, 1]. Ray 5 images 0's surface at
  // centre x = 3.6, between its last pixel and 1's first: the centre's grid cannot tell on which side the edge is,
  // so a refined 0 there stays. At ray 6 (x = 4.6, both pixels 1's) it does not.
  cv::Mat disparity(1, kWidth, CV_32F, cv::Scalar(-0.4f));
  disparity.colRange(0, 4).setTo(1.4f);
  Labels labels = ThreeViews({0, 0, 0, 1, 0, 0, 0, 1}, kCentre, kCentre);
  CarryCentreToSideViews(disparity, Planes(1.4, -0.4), labels);
  // Ray 3 is 0's in front: the refined 1 behind it is hidden there and gives way.
  EXPECT_EQ(View(labels, 0), (std::vector<std::int32_t>{0, 0, 0, 0, 0, 0, 1, 1}));
}

}  // namespace
}  // namespace lfsp::segment
