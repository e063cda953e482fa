// The geometry of the occlusion handling: which views each subset of the angular patch holds, and how far from an
// edge it is used.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "lfsp/depth/occlusion.h"

namespace lfsp::depth {
namespace {

constexpr double kPi = std::numbers::pi;

// The views along an edge are those whose offsets are parallel to it, whichever way its gradient points.
TEST(Occlusion, ViewsAlongAnEdgeRunParallelToIt) {
  const int vertical = SectorOfOffset(0, 1) % (kSectors / 2);  // views straight above and below the centre
  const int horizontal = SectorOfOffset(1, 0) % (kSectors / 2);
  for (const double normal : {0.0, kPi, -kPi, 0.05, kPi - 0.05}) {  // a vertical edge: the gradient along x
    EXPECT_EQ(AlongPairForEdgeNormal(normal), vertical) << normal;
  }
  for (const double normal : {kPi / 2, -kPi / 2, kPi / 2 + 0.05, -kPi / 2 - 0.05}) {  // a horizontal edge
    EXPECT_EQ(AlongPairForEdgeNormal(normal), horizontal) << normal;
  }
  // A diagonal edge (gradient towards +x+y) runs along the offset (1, -1).
  EXPECT_EQ(AlongPairForEdgeNormal(kPi / 4), SectorOfOffset(1, -1) % (kSectors / 2));
}

TEST(Occlusion, AutomaticRadiusIsTheLargestShiftPlusTheBlur) {
  // 9x9 views: an outer view is 4 steps from the centre; a range of 2 px per step moves the background 8 px.
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(9, 9, -1.0f, 1.0f), 8.0);
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(9, 9, -1.0f, 1.0f, 2.5), 13.0);  // presmoothing spreads the edge 2 sigma
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(9, 9, -3.3f, 2.8f), kMaxAutomaticOcclusionRadius);
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(3, 3, 0.0f, 0.5f), 2.0);  // at least 2 px
  // 8x8 views: the centre view is (3, 3), so view 7 is 4 steps away on that side.
  EXPECT_DOUBLE_EQ(AutomaticOcclusionRadius(8, 8, -1.0f, 1.0f), 8.0);
}

TEST(Occlusion, LongestViewOffsetIsTheFarthestCornerView) {
  EXPECT_DOUBLE_EQ(LongestViewOffset(9, 9), 4.0 * std::numbers::sqrt2);
  EXPECT_DOUBLE_EQ(LongestViewOffset(8, 8), 4.0 * std::numbers::sqrt2);  // centre (3, 3), view (7, 7)
  EXPECT_DOUBLE_EQ(LongestViewOffset(7, 5), std::hypot(3.0, 2.0));
  EXPECT_DOUBLE_EQ(LongestViewOffset(2, 1), 1.0);
}

// A comb of 1 px teeth with 1 px gaps in front of a smooth random texture, as the simulator's comb scene: teeth along
// y (`vertical`) or along x. Returns the centre view and the comb's rectangle.
std::pair<cv::Mat, cv::Rect> CombInFrontOfTexture(bool vertical) {
  constexpr int kSize = 96;
  cv::Mat noise(kSize, kSize, CV_32FC3);
  cv::RNG rng(19);
  rng.fill(noise, cv::RNG::UNIFORM, cv::Scalar::all(0.0), cv::Scalar::all(1.0));
  cv::Mat view;
  cv::GaussianBlur(noise, view, cv::Size(), 2.0);
  view = (view - cv::Scalar::all(0.5)) * 6.0 + cv::Scalar::all(0.5);  // the blur left about a tenth of the contrast
  const cv::Rect comb(28, 20, 40, 56);
  for (int y = comb.y; y < comb.y + comb.height; ++y)
    for (int x = comb.x; x < comb.x + comb.width; x += 2) view.at<cv::Vec3f>(y, x) = {0.8f, 0.3f, 0.2f};
  if (vertical) return {view, comb};
  cv::Mat transposed;
  cv::transpose(view, transposed);
  return {transposed, cv::Rect(comb.y, comb.x, comb.height, comb.width)};
}

// Inside a comb of 1 px teeth, every pixel must use the views along the teeth: the gaps are hidden from all the
// others. Found from the smoothed gradient, as before, the edges Canny finds there (the texture seen through the
// gaps) pointed anywhere, and the simulator's comb read its 1 px gaps as the teeth.
TEST(Occlusion, ViewsAlongTheTeethOfAOnePixelComb) {
  for (const bool vertical : {true, false}) {
    const auto [view, comb] = CombInFrontOfTexture(vertical);
    OcclusionOptions options;
    options.radius = 6.0;
    const OcclusionMap map = DetectOcclusionEdges(view, options);
    const int along_teeth = SectorOfOffset(vertical ? 0 : 1, vertical ? 1 : 0) % (kSectors / 2);
    int checked = 0, wrong = 0;
    for (int y = comb.y + 2; y < comb.y + comb.height - 2; ++y)
      for (int x = comb.x + 2; x < comb.x + comb.width - 2; ++x) {
        if (map.candidate.at<std::uint8_t>(y, x) == 0) continue;
        ++checked;
        if (map.along.at<std::uint8_t>(y, x) != along_teeth) ++wrong;
      }
    EXPECT_GT(checked, 1000) << (vertical ? "vertical" : "horizontal");
    EXPECT_EQ(wrong, 0) << (vertical ? "vertical" : "horizontal") << " teeth: " << wrong << " of " << checked;
  }
}

}  // namespace
}  // namespace lfsp::depth
