// Unit tests of segment/src/warp.h (issue 14 item 5): ForwardWarp, the projection of centre-view labels into a side
// view along their disparity (front-most wins), and FillHoles, which fills what nothing lands on from the background
// side of the epipolar line. Inputs are a few hand-placed pixels whose landing spots follow from the docs/DESIGN.md
// convention (core/include/lfsp/core/conventions.h): (x0, y0) with disparity d lands at (x0 - du d, y0 - dv d).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "lfsp/core/conventions.h"
#include "warp.h"

namespace lfsp::segment {
namespace {

constexpr float kNoDepth = -std::numeric_limits<float>::infinity();

// A width x height centre view with every pixel unlabelled (-1) unless set.
struct Centre {
  int width;
  int height;
  std::vector<std::int32_t> labels;
  std::vector<float> disparity;
  Centre(int w, int h, std::int32_t label = -1, float d = 0.0f)
      : width(w),
        height(h),
        labels(static_cast<std::size_t>(w * h), label),
        disparity(static_cast<std::size_t>(w * h), d) {}
  void Set(int x, int y, std::int32_t label, float d) {
    labels[static_cast<std::size_t>(y * width + x)] = label;
    disparity[static_cast<std::size_t>(y * width + x)] = d;
  }
};

struct View {
  std::vector<std::int32_t> labels;
  std::vector<float> depth;
  int width = 0;
  std::int32_t Label(int x, int y) const { return labels[static_cast<std::size_t>(y * width + x)]; }
  float Depth(int x, int y) const { return depth[static_cast<std::size_t>(y * width + x)]; }
  int Labelled() const {
    int n = 0;
    for (std::int32_t label : labels) n += label >= 0;
    return n;
  }
};

View Warp(const Centre& centre, int du, int dv) {
  View view;
  view.width = centre.width;
  view.labels.assign(centre.labels.size(), 12345);  // garbage: ForwardWarp must reset every pixel
  view.depth.assign(centre.labels.size(), 99.0f);
  ForwardWarp(centre.labels.data(), centre.disparity.data(), centre.width, centre.height, du, dv, view.labels.data(),
              view.depth.data());
  return view;
}

// --- ForwardWarp ---

TEST(ForwardWarp, APixelLandsAtXMinusDuDAndYMinusDvD) {
  Centre centre(10, 8);
  centre.Set(5, 4, 7, 1.0f);
  const View view = Warp(centre, 2, -1);  // view (u, v) = (uc + 2, vc - 1)
  const PixelPosition expected = ProjectFromCentre({5.0f, 4.0f}, 1.0f, {4 + 2, 4 - 1}, {4, 4});
  ASSERT_EQ(expected.x, 3.0f);
  ASSERT_EQ(expected.y, 5.0f);
  EXPECT_EQ(view.Label(3, 5), 7);
  EXPECT_EQ(view.Depth(3, 5), 1.0f);
  EXPECT_EQ(view.Labelled(), 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 10; ++x) {
      if (x == 3 && y == 5) continue;
      EXPECT_EQ(view.Label(x, y), -1) << x << "," << y;
      EXPECT_EQ(view.Depth(x, y), kNoDepth) << x << "," << y;
    }
}

TEST(ForwardWarp, NegativeDisparityMovesWithTheViewOffset) {
  Centre centre(10, 8);
  centre.Set(5, 4, 3, -1.5f);
  const View view = Warp(centre, -2, 2);  // lands at (5 - 3, 4 + 3)
  EXPECT_EQ(view.Label(2, 7), 3);
  EXPECT_EQ(view.Depth(2, 7), -1.5f);
  EXPECT_EQ(view.Labelled(), 1);
}

TEST(ForwardWarp, TheCentreViewOffsetIsTheIdentity) {
  Centre centre(6, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 6; ++x) centre.Set(x, y, y * 6 + x, 0.5f * static_cast<float>(x - y));
  const View view = Warp(centre, 0, 0);
  EXPECT_EQ(view.labels, centre.labels);
  EXPECT_EQ(view.depth, centre.disparity);
}

TEST(ForwardWarp, RoundsToTheNearestPixel) {
  // du = 2: d = 0.2 shifts by -0.4 (stays), d = 0.3 by -0.6 (one pixel left), d = 0.7 by -1.4 (one pixel left),
  // d = 0.8 by -1.6 (two pixels left). One pixel per row so nothing collides.
  Centre centre(10, 4);
  centre.Set(5, 0, 0, 0.2f);
  centre.Set(5, 1, 1, 0.3f);
  centre.Set(5, 2, 2, 0.7f);
  centre.Set(5, 3, 3, 0.8f);
  const View view = Warp(centre, 2, 0);
  EXPECT_EQ(view.Label(5, 0), 0);
  EXPECT_EQ(view.Label(4, 1), 1);
  EXPECT_EQ(view.Label(4, 2), 2);
  EXPECT_EQ(view.Label(3, 3), 3);
  EXPECT_EQ(view.Labelled(), 4);
}

TEST(ForwardWarp, ExactHalvesRoundTowardsPositiveCoordinates) {
  // A shift of exactly -0.5 or +0.5 (d = 0.25 at du = +-2) rounds up, towards +x, in both directions
  // (floor(x + 0.5)): a rule to pin, since a change would move every tie by one pixel.
  Centre centre(10, 2);
  centre.Set(5, 0, 0, 0.25f);
  centre.Set(5, 1, 1, 0.25f);
  const View left = Warp(centre, 2, 0);    // 5 - 0.5 = 4.5 -> 5
  const View right = Warp(centre, -2, 0);  // 5 + 0.5 = 5.5 -> 6
  EXPECT_EQ(left.Label(5, 0), 0);
  EXPECT_EQ(right.Label(6, 1), 1);
  const View up = Warp(centre, 0, 2);  // rows: 0 - 0.5 -> 0, 1 - 0.5 -> 1
  EXPECT_EQ(up.Label(5, 0), 0);
  EXPECT_EQ(up.Label(5, 1), 1);
}

TEST(ForwardWarp, PixelsLandingOutsideTheViewAreDropped) {
  Centre centre(6, 4);
  centre.Set(0, 0, 1, 1.0f);   // du = 1: lands at x = -1
  centre.Set(5, 3, 2, -1.0f);  // lands at x = 6
  centre.Set(3, 2, 3, 0.0f);   // stays
  const View view = Warp(centre, 1, 0);
  EXPECT_EQ(view.Labelled(), 1);
  EXPECT_EQ(view.Label(3, 2), 3);
}

TEST(ForwardWarp, AtTheLeftAndTopBordersLessThanHalfAPixelOutsideRoundsIn) {
  // du = 2 from column 0: d = 0.2 shifts to -0.4 (rounds to 0), d = 0.25 to exactly -0.5 (to 0, ties go towards +x),
  // d = 0.3 to -0.6 (-1, dropped). The same along rows with dv = 2. Around 0 the nearest pixel is where truncating
  // towards zero and the floor differ, so this pins the bounds test that lets ForwardWarp truncate.
  for (const bool along_rows : {false, true}) {
    // Pixel i of the line on the border sits at (0, i) for du = 2, at (i, 0) for dv = 2.
    Centre centre(along_rows ? 3 : 4, along_rows ? 4 : 3);
    const auto at = [&](int i) { return along_rows ? std::pair{i, 0} : std::pair{0, i}; };
    const float disparities[] = {0.2f, 0.25f, 0.3f};
    for (int i = 0; i < 3; ++i) centre.Set(at(i).first, at(i).second, i, disparities[i]);
    const View view = Warp(centre, along_rows ? 0 : 2, along_rows ? 2 : 0);
    EXPECT_EQ(view.Label(at(0).first, at(0).second), 0) << (along_rows ? "dv" : "du");
    EXPECT_EQ(view.Label(at(1).first, at(1).second), 1) << (along_rows ? "dv" : "du");
    EXPECT_EQ(view.Labelled(), 2) << (along_rows ? "dv" : "du");
  }
}

TEST(ForwardWarp, UnlabelledAndNonFiniteSamplesAreSkipped) {
  Centre centre(6, 4);
  centre.Set(1, 1, -1, 0.0f);
  centre.Set(2, 1, 4, std::numeric_limits<float>::quiet_NaN());
  centre.Set(3, 1, 5, std::numeric_limits<float>::infinity());
  centre.Set(4, 1, 6, 0.0f);
  const View view = Warp(centre, 1, 1);
  EXPECT_EQ(view.Labelled(), 1);
  EXPECT_EQ(view.Label(4, 1), 6);
}

TEST(ForwardWarp, TheNearerSurfaceWinsWhenScannedLast) {
  // du = 2: background label 1 at x0 = 2 (d = 0) stays at 2; foreground label 2 at x0 = 4 (d = 1) lands on 2 too.
  Centre centre(8, 1);
  centre.Set(2, 0, 1, 0.0f);
  centre.Set(4, 0, 2, 1.0f);
  const View view = Warp(centre, 2, 0);
  EXPECT_EQ(view.Label(2, 0), 2);
  EXPECT_EQ(view.Depth(2, 0), 1.0f);
  EXPECT_EQ(view.Labelled(), 1);
}

TEST(ForwardWarp, TheNearerSurfaceWinsWhenScannedFirst) {
  // du = -2: foreground label 2 at x0 = 0 (d = 1) lands on 2, then background label 1 at x0 = 2 (d = 0) stays at 2.
  Centre centre(8, 1);
  centre.Set(0, 0, 2, 1.0f);
  centre.Set(2, 0, 1, 0.0f);
  const View view = Warp(centre, -2, 0);
  EXPECT_EQ(view.Label(2, 0), 2);
  EXPECT_EQ(view.Depth(2, 0), 1.0f);
  EXPECT_EQ(view.Labelled(), 1);
}

TEST(ForwardWarp, AForegroundStripOccludesAndDisoccludesTheBackground) {
  // One row of 12: background label 0 (d = 0) everywhere except the foreground label 1 (d = 2) at x0 = 5, 6.
  // In the view du = 1 the strip moves to x = 3, 4, hiding the background there, and uncovers x = 5, 6.
  Centre centre(12, 1, 0, 0.0f);
  centre.Set(5, 0, 1, 2.0f);
  centre.Set(6, 0, 1, 2.0f);
  const View view = Warp(centre, 1, 0);
  const std::vector<std::int32_t> expected{0, 0, 0, 1, 1, -1, -1, 0, 0, 0, 0, 0};
  EXPECT_EQ(view.labels, expected);
  EXPECT_EQ(view.Depth(3, 0), 2.0f);
  EXPECT_EQ(view.Depth(5, 0), kNoDepth);
}

// --- FillHoles ---

View Row(const std::vector<std::int32_t>& labels, const std::vector<float>& depth) {
  View view;
  view.labels = labels;
  view.depth = depth;
  view.width = static_cast<int>(labels.size());
  return view;
}

void Fill(View& view, int height, int du, int dv, int max_steps) {
  FillHoles(view.labels.data(), view.depth.data(), view.width, height, du, dv, max_steps);
}

TEST(FillHoles, ADisocclusionTakesTheBackgroundSide) {
  // Background label 0 (depth 0) on the left, foreground label 1 (depth 2) on the right, a hole between.
  View view = Row({0, 0, 0, 0, -1, -1, 1, 1, 1, 1}, {0, 0, 0, 0, kNoDepth, kNoDepth, 2, 2, 2, 2});
  Fill(view, 1, 1, 0, 20);
  EXPECT_EQ(view.labels, (std::vector<std::int32_t>{0, 0, 0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(view.Depth(4, 0), 0.0f);
  EXPECT_EQ(view.Depth(5, 0), 0.0f);
}

TEST(FillHoles, TheBackgroundSideIsChosenByDepthNotByDirection) {
  // The same hole with the foreground on the left: the right-hand label now fills it.
  View view = Row({1, 1, 1, 1, -1, -1, 0, 0, 0, 0}, {2, 2, 2, 2, kNoDepth, kNoDepth, 0, 0, 0, 0});
  Fill(view, 1, 1, 0, 20);
  EXPECT_EQ(view.labels, (std::vector<std::int32_t>{1, 1, 1, 1, 0, 0, 0, 0, 0, 0}));
}

TEST(FillHoles, SearchesAlongTheEpipolarLineOnly) {
  // 5x5, one hole at (2, 2). Along the vertical line (du = 0, dv = 1): label 1 above (depth 1) and label 2 below
  // (depth 0.5); across the line, label 3 left and right is further back (depth -5) but not on the line.
  const int w = 5;
  View view;
  view.width = w;
  view.labels.assign(25, 3);
  view.depth.assign(25, -5.0f);
  for (int x = 0; x < w; ++x) {
    view.labels[static_cast<std::size_t>(1 * w + x)] = 1;
    view.depth[static_cast<std::size_t>(1 * w + x)] = 1.0f;
    view.labels[static_cast<std::size_t>(3 * w + x)] = 2;
    view.depth[static_cast<std::size_t>(3 * w + x)] = 0.5f;
  }
  view.labels[12] = -1;
  view.depth[12] = kNoDepth;
  View vertical = view;
  Fill(vertical, 5, 0, 1, 10);
  EXPECT_EQ(vertical.Label(2, 2), 2);
  EXPECT_EQ(vertical.Depth(2, 2), 0.5f);
  View horizontal = view;  // along the row the neighbours are label 3 on both sides
  Fill(horizontal, 5, -1, 0, 10);
  EXPECT_EQ(horizontal.Label(2, 2), 3);
  EXPECT_EQ(horizontal.Depth(2, 2), -5.0f);
}

TEST(FillHoles, FollowsADiagonalEpipolarLine) {
  // du = dv = 1: the hole at (2, 2) looks at (1, 1) / (3, 3), not at its 4-neighbours.
  const int w = 5;
  View view;
  view.width = w;
  view.labels.assign(25, 4);
  view.depth.assign(25, -9.0f);
  view.labels[1 * w + 1] = 5;
  view.depth[1 * w + 1] = 3.0f;
  view.labels[3 * w + 3] = 6;
  view.depth[3 * w + 3] = 1.0f;
  view.labels[2 * w + 2] = -1;
  view.depth[2 * w + 2] = kNoDepth;
  Fill(view, 5, 1, 1, 10);
  EXPECT_EQ(view.Label(2, 2), 6);
  EXPECT_EQ(view.Depth(2, 2), 1.0f);
}

TEST(FillHoles, HolesBeyondReachTakeTheNearestLabelBreadthFirst) {
  // Label 0 (depth 0) at x = 0 and label 1 (depth 5) at x = 9, holes between. With reach 3 only x = 1..3 see label 0
  // and x = 6..8 label 1 along the line; x = 4, 5 see nothing and take their nearest labelled pixel.
  const std::vector<std::int32_t> labels{0, -1, -1, -1, -1, -1, -1, -1, -1, 1};
  const std::vector<float> depth{0, kNoDepth, kNoDepth, kNoDepth, kNoDepth, kNoDepth, kNoDepth, kNoDepth, kNoDepth, 5};
  View near = Row(labels, depth);
  Fill(near, 1, 1, 0, 3);
  EXPECT_EQ(near.labels, (std::vector<std::int32_t>{0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
  EXPECT_EQ(near.Depth(4, 0), 0.0f);
  EXPECT_EQ(near.Depth(5, 0), 5.0f);
  // With reach enough for the whole row every hole sees both ends and takes the background, label 0.
  View far = Row(labels, depth);
  Fill(far, 1, 1, 0, 20);
  EXPECT_EQ(far.labels, (std::vector<std::int32_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 1}));
}

TEST(FillHoles, AHoleRowAtTheBorderIsFilledFromTheNearestRow) {
  // du = 1: the top row is all holes, so nothing lies on its epipolar line (the row itself); the breadth-first
  // fallback fills it from the row below.
  const int w = 4, h = 3;
  View view;
  view.width = w;
  view.labels = {-1, -1, -1, -1, 7, 7, 8, 8, 9, 9, 9, 9};
  view.depth = {kNoDepth, kNoDepth, kNoDepth, kNoDepth, 1, 1, 2, 2, 3, 3, 3, 3};
  Fill(view, h, 1, 0, 10);
  EXPECT_EQ(view.labels, (std::vector<std::int32_t>{7, 7, 8, 8, 7, 7, 8, 8, 9, 9, 9, 9}));
  EXPECT_EQ(view.Depth(2, 0), 2.0f);
}

TEST(FillHoles, WithoutHolesNothingChanges) {
  View view = Row({0, 1, 2, 3}, {0.5f, 1, 2, 3});
  const View before = view;
  Fill(view, 1, 1, 0, 10);
  EXPECT_EQ(view.labels, before.labels);
  EXPECT_EQ(view.depth, before.depth);
}

TEST(FillHoles, WithoutAnyLabelNothingChanges) {
  View view = Row({-1, -1, -1}, {kNoDepth, kNoDepth, kNoDepth});
  Fill(view, 1, 1, 0, 10);
  EXPECT_EQ(view.labels, (std::vector<std::int32_t>{-1, -1, -1}));
  EXPECT_EQ(view.Depth(1, 0), kNoDepth);
}

TEST(FillHoles, TheCentreOffsetUsesOnlyTheNearestFill) {
  // du = dv = 0 has no epipolar line: holes take the nearest labelled pixel.
  View view = Row({4, -1, -1, -1, -1, 6}, {1, kNoDepth, kNoDepth, kNoDepth, kNoDepth, 0});
  Fill(view, 1, 0, 0, 10);
  EXPECT_EQ(view.labels, (std::vector<std::int32_t>{4, 4, 4, 6, 6, 6}));
}

TEST(WarpAndFill, AForegroundStripLeavesItsDisocclusionToTheBackground) {
  // The strip of ForwardWarp's test above: the uncovered x = 5, 6 belong to the background label 0, not the strip.
  Centre centre(12, 1, 0, 0.0f);
  centre.Set(5, 0, 1, 2.0f);
  centre.Set(6, 0, 1, 2.0f);
  View view = Warp(centre, 1, 0);
  Fill(view, 1, 1, 0, 10);
  EXPECT_EQ(view.labels, (std::vector<std::int32_t>{0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0}));
}

}  // namespace
}  // namespace lfsp::segment
