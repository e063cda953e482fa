// CarryCentreLabels, the reference segmentation of self-similarity: rays the centre view sees take the centre label
// of their scene point exactly; rays it does not see take the background's.

#include <gtest/gtest.h>

#include "lfsp/segment/metrics.h"

namespace lfsp::segment {
namespace {

constexpr int kViews = 5, kSize = 24, kBlock = 6;

// Centre labels: a 4x4 grid of 6x6 blocks.
Labels GridLabels() {
  Labels labels(LightFieldShape{kViews, kViews, kSize, kSize, 1}, 0);
  const ViewIndex c = labels.shape().Centre();
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) labels.at(c, y, x) = (y / kBlock) * (kSize / kBlock) + x / kBlock;
  return labels;
}

TEST(CarryCentreLabels, ShiftsLabelsExactlyOnAPlane) {
  const Labels labels = GridLabels();
  const DisparityMap disparity(kSize, kSize, 1.0f);  // one pixel per view step
  const std::vector<DisparityMap> views = PropagateDisparity(disparity, labels.shape());
  const Labels carried = CarryCentreLabels(labels, disparity, views);
  const ViewIndex c = labels.shape().Centre();
  for (int v = 0; v < kViews; ++v)
    for (int u = 0; u < kViews; ++u)
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
          const int x0 = x + (u - c.u), y0 = y + (v - c.v);  // the project's sign: x_c = x + du * d
          if (x0 < 0 || y0 < 0 || x0 >= kSize || y0 >= kSize) {
            EXPECT_GE(carried.at({u, v}, y, x), 0) << "rays outside the centre frame are filled";
          } else {
            ASSERT_EQ(carried.at({u, v}, y, x), labels.at(c, y0, x0)) << u << "," << v << " " << x << "," << y;
          }
        }
  // Interior blocks keep their whole slice in every view, so only the border blocks are off, far less than for
  // labels that stay put in every view instead of following the shift.
  Labels still(labels.shape(), 0);
  for (int v = 0; v < kViews; ++v)
    for (int u = 0; u < kViews; ++u)
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) still.at({u, v}, y, x) = labels.at(c, y, x);
  const double self_similarity = SelfSimilarity(carried, views), still_similarity = SelfSimilarity(still, views);
  RecordProperty("self_similarity", std::to_string(self_similarity));
  RecordProperty("still_self_similarity", std::to_string(still_similarity));
  EXPECT_GT(self_similarity, 0.0);
  EXPECT_LT(self_similarity, 0.5 * still_similarity);
}

TEST(CarryCentreLabels, UncoveredBackgroundTakesABackgroundLabel) {
  Labels labels = GridLabels();
  DisparityMap disparity(kSize, kSize, 0.0f);
  const ViewIndex c = labels.shape().Centre();
  // A foreground square (label 99) at 2 px per view step over the middle of a still background.
  for (int y = 8; y < 16; ++y)
    for (int x = 8; x < 16; ++x) {
      disparity.at(y, x) = 2.0f;
      labels.at(c, y, x) = 99;
    }
  const std::vector<DisparityMap> views = PropagateDisparity(disparity, labels.shape());
  const Labels carried = CarryCentreLabels(labels, disparity, views);
  // In the rightmost view (du = 2) the square moves 4 px left (x_view = x_c - du * d): the background at x 12..15
  // that it hid in the centre view is uncovered.
  const ViewIndex right{kViews - 1, c.v};
  for (int y = 8; y < 16; ++y) {
    for (int x = 4; x < 12; ++x) EXPECT_EQ(carried.at(right, y, x), 99) << x << "," << y;
    for (int x = 12; x < 16; ++x) {
      EXPECT_NE(carried.at(right, y, x), 99) << "uncovered background, " << x << "," << y;
      EXPECT_EQ(carried.at(right, y, x), labels.at(c, y, 16)) << "the background beyond the square, " << x;
    }
  }
}

}  // namespace
}  // namespace lfsp::segment
