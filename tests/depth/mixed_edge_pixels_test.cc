// The occlusion edge's mixed pixels given back to the farther surface (mixed_edge_pixels.h), on a vertical edge
// drawn by hand: a foreground at disparity 1 on the left, a background at 0 on the right, the true edge between
// columns 19 and 20, and the foreground's disparity read over columns that are (mostly) background.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/depth/mixed_edge_pixels.h"

namespace lfsp::depth {
namespace {

constexpr int kSize = 40;
const cv::Vec3f kRed{0.8f, 0.2f, 0.2f};
const cv::Vec3f kBlue{0.2f, 0.2f, 0.8f};

cv::Vec3f Mix(const cv::Vec3f& near, const cv::Vec3f& far, float share) { return share * near + (1.0f - share) * far; }

// Columns below `edge` are `near`, the rest `far`; every pixel left of `fat_until` reads disparity 1, the rest 0.
struct Edge {
  cv::Mat guide;
  DisparityMap disparity;
  Edge(const cv::Vec3f& near, const cv::Vec3f& far, int edge, int fat_until)
      : guide(kSize, kSize, CV_32FC3), disparity(kSize, kSize, 0.0f) {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        guide.at<cv::Vec3f>(y, x) = x < edge ? near : far;
        disparity.at(y, x) = x < fat_until ? 1.0f : 0.0f;
      }
  }
  void SetColumn(int x, const cv::Vec3f& colour) {
    for (int y = 0; y < kSize; ++y) guide.at<cv::Vec3f>(y, x) = colour;
  }
  float At(int x) const { return disparity.at(kSize / 2, x); }
};

TEST(MixedEdgePixels, AMostlyFartherPixelMovesAndAMostlyNearerOneStays) {
  Edge edge(kRed, kBlue, 20, 21);  // column 20 is background in colour but reads the foreground's disparity
  edge.SetColumn(20, Mix(kRed, kBlue, 1.0f / 3.0f));
  EXPECT_EQ(ReassignMixedEdgePixels(edge.disparity, edge.guide), kSize);
  EXPECT_EQ(edge.At(20), 0.0f);
  EXPECT_EQ(edge.At(19), 1.0f);

  Edge nearer(kRed, kBlue, 20, 21);
  nearer.SetColumn(20, Mix(kRed, kBlue, 2.0f / 3.0f));  // two thirds the foreground's: it keeps its disparity
  EXPECT_EQ(ReassignMixedEdgePixels(nearer.disparity, nearer.guide), 0);
  EXPECT_EQ(nearer.At(20), 1.0f);
}

TEST(MixedEdgePixels, ATwoPixelFatteningMovesOverTwoRounds) {
  Edge edge(kRed, kBlue, 20, 22);  // columns 20 and 21 read the foreground's disparity
  edge.SetColumn(20, Mix(kRed, kBlue, 1.0f / 3.0f));
  MixedEdgeOptions one_round;
  one_round.rounds = 1;
  DisparityMap first = edge.disparity;
  ReassignMixedEdgePixels(first, edge.guide, one_round);
  EXPECT_EQ(first.at(kSize / 2, 21), 0.0f);
  EXPECT_EQ(first.at(kSize / 2, 20), 1.0f) << "column 20 is no edge pixel until column 21 has moved";
  EXPECT_EQ(ReassignMixedEdgePixels(edge.disparity, edge.guide), 2 * kSize);
  EXPECT_EQ(edge.At(21), 0.0f);
  EXPECT_EQ(edge.At(20), 0.0f);
  EXPECT_EQ(edge.At(19), 1.0f);
}

// A rim that turns away from the light is darker but keeps its surface's chromaticity: its RGB lies a third of the
// way from the dark background to the foreground (as a mixed pixel's would), its chromaticity is the foreground's.
TEST(MixedEdgePixels, AShadedRimKeepsItsDisparity) {
  const cv::Vec3f dark_blue{0.1f, 0.1f, 0.4f};
  Edge edge(kRed, dark_blue, 21, 21);  // the true edge at 21: column 20 is foreground, shaded
  // Its RGB share: (0.35 F - B) . (F - B) / |F - B|^2 = 0.189 / 0.54 = 0.35, under 0.4; its chromaticity share is 1.
  edge.SetColumn(20, 0.35f * kRed);
  EXPECT_EQ(ReassignMixedEdgePixels(edge.disparity, edge.guide), 0);
  EXPECT_EQ(edge.At(20), 1.0f);
}

TEST(MixedEdgePixels, SidesOfOneChromaticityDoNotDecide) {
  const cv::Vec3f light_grey{0.6f, 0.6f, 0.6f}, dark_grey{0.3f, 0.3f, 0.3f};
  Edge edge(light_grey, dark_grey, 20, 21);
  edge.SetColumn(20, Mix(light_grey, dark_grey, 0.2f));  // RGB share 0.2, but the chromaticities are the same
  EXPECT_EQ(ReassignMixedEdgePixels(edge.disparity, edge.guide), 0);
  EXPECT_EQ(edge.At(20), 1.0f);
}

// Each side stands for one surface only where it is even in disparity over `depth` pixels: a red thing nearer still
// right behind the edge pixel (a strip of foreground no wider than two pixels), a farther side that steps again,
// or a side pixel of unknown disparity, and the pixel stays.
TEST(MixedEdgePixels, SidesThatAreNotEvenDoNotDecide) {
  const auto at_column = [](Edge& edge, int x, float value) {
    for (int y = 0; y < kSize; ++y) edge.disparity.at(y, x) = value;
  };
  const auto fattened = [] {
    Edge edge(kRed, kBlue, 20, 21);
    edge.SetColumn(20, Mix(kRed, kBlue, 1.0f / 3.0f));
    return edge;
  };
  Edge nearer_behind = fattened();
  at_column(nearer_behind, 18, 2.0f);
  Edge farther_steps = fattened();
  at_column(farther_steps, 22, -1.0f);
  Edge unknown_behind = fattened();
  at_column(unknown_behind, 19, std::numeric_limits<float>::quiet_NaN());
  for (Edge* edge : {&nearer_behind, &farther_steps, &unknown_behind}) {
    EXPECT_EQ(ReassignMixedEdgePixels(edge->disparity, edge->guide), 0);
    EXPECT_EQ(edge->At(20), 1.0f);
  }
}

TEST(MixedEdgePixels, OffAndNonFiniteDisparitiesLeaveTheMapAsItWas) {
  Edge edge(kRed, kBlue, 20, 21);
  edge.SetColumn(20, Mix(kRed, kBlue, 1.0f / 3.0f));
  MixedEdgeOptions off;
  off.max_share = 0.0f;
  EXPECT_EQ(ReassignMixedEdgePixels(edge.disparity, edge.guide, off), 0);
  EXPECT_EQ(edge.At(20), 1.0f);

  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int y = 0; y < kSize; ++y) edge.disparity.at(y, 21) = nan;  // the farther neighbour unknown
  EXPECT_EQ(ReassignMixedEdgePixels(edge.disparity, edge.guide), 0);
  EXPECT_EQ(edge.At(20), 1.0f);
  EXPECT_TRUE(std::isnan(edge.At(21)));
}

TEST(MixedEdgePixels, RefusesAGuideOfAnotherSize) {
  Edge edge(kRed, kBlue, 20, 21);
  const cv::Mat small(kSize / 2, kSize, CV_32FC3, cv::Scalar::all(0.5));
  EXPECT_THROW(ReassignMixedEdgePixels(edge.disparity, small), Error);
}

}  // namespace
}  // namespace lfsp::depth
