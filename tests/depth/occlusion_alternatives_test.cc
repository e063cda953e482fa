// Which partial angular patches a pixel near an edge may use: refused on a thin structure in front of the disparity
// they prefer, admitted in a gap between two occluders and beside a single one.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/depth/occlusion_alternatives.h"

namespace lfsp::depth {
namespace {

constexpr int kWidth = 16;
constexpr int kHeight = 3;
const std::vector<float> kDisparities = {-1.0f, 0.0f, 1.0f};  // background, -, structure in front
const cv::Vec3f kGrey(0.5f, 0.5f, 0.5f);
const cv::Vec3f kRed(0.9f, 0.1f, 0.1f);
const double kLongestViewOffset = 4.0 * std::numbers::sqrt2;  // 9 x 9 views

// A layout across the edges: for each position, the whole patch's disparity and the centre view's colour (Scene
// lays it out along x, along y or along the diagonal).
struct Layout {
  std::vector<float> disparity;
  std::vector<cv::Vec3f> colour;
};

// How the row layout lies in the image: along x (vertical edges, normal along x), along y (horizontal edges, the
// scene transposed) or along the diagonal (edges running from top right to bottom left, normal at 45 degrees
// towards +x and +y: the layout's position at pixel (x, y) is (x + y) / 2).
enum class Orientation { kColumns, kRows, kDiagonal };

// Every pixel an occlusion candidate beside an edge across the layout. The whole patch prefers each pixel's
// disparity in `layout`; both partial patches prefer the background's.
struct Scene {
  explicit Scene(const Layout& layout, Orientation lying = Orientation::kColumns)
      : orientation(lying),
        width(lying == Orientation::kRows ? kHeight : kWidth),
        height(lying == Orientation::kColumns ? kHeight : kWidth),
        cost(width, height, 3),
        whole_patch(width, height),
        centre(height, width, CV_32FC3) {
    const double normal = orientation == Orientation::kColumns ? 0.0
                          : orientation == Orientation::kRows  ? std::numbers::pi / 2
                                                               : std::numbers::pi / 4;
    occlusion.candidate = cv::Mat(height, width, CV_8U, cv::Scalar(255));
    occlusion.split = cv::Mat(height, width, CV_8U, cv::Scalar(0));
    occlusion.along = cv::Mat(height, width, CV_8U, cv::Scalar(AlongPairForEdgeNormal(normal)));
    alternatives.half = CostVolume(width, height, 3, std::numeric_limits<float>::infinity());
    alternatives.along = CostVolume(width, height, 3, std::numeric_limits<float>::infinity());
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const auto position = static_cast<std::size_t>(Position(x, y));
        const float d = layout.disparity[position];
        whole_patch.at(y, x) = d;
        centre.at<cv::Vec3f>(y, x) = layout.colour[position];
        for (int l = 0; l < 3; ++l) {
          cost.Curve(y, x)[l] = kDisparities[static_cast<std::size_t>(l)] == d ? 0.3f : 0.6f;
          alternatives.half.Curve(y, x)[l] = l == 0 ? 0.1f : 0.7f;
          alternatives.along.Curve(y, x)[l] = l == 0 ? 0.2f : 0.8f;
        }
      }
    }
  }
  // The layout's position at pixel (x, y).
  int Position(int x, int y) const {
    switch (orientation) {
      case Orientation::kColumns:
        return x;
      case Orientation::kRows:
        return y;
      case Orientation::kDiagonal:
        return (x + y) / 2;
    }
    return x;
  }
  // The label the curve at pixel (x, y) now prefers.
  int PreferredAt(int x, int y) const {
    const float* curve = cost.Curve(y, x);
    return static_cast<int>(std::min_element(curve, curve + 3) - curve);
  }
  // The same in the middle line across a column or row layout, at `position`.
  int Preferred(int position) const {
    return orientation == Orientation::kRows ? PreferredAt(1, position) : PreferredAt(position, 1);
  }
  int Admit(const ThinStructureOptions& options = {}, const OccluderHorizonOptions& horizon = {}) {
    return AdmitOcclusionAlternatives(cost, alternatives, whole_patch, kDisparities, occlusion, centre, options,
                                      horizon, kLongestViewOffset);
  }

  Orientation orientation;
  int width, height;
  CostVolume cost;
  OcclusionAlternatives alternatives;
  DisparityMap whole_patch;
  cv::Mat centre;
  OcclusionMap occlusion;
};

// Every column grey background at -1.
Layout Background() { return {std::vector<float>(kWidth, -1.0f), std::vector<cv::Vec3f>(kWidth, kGrey)}; }

// Positions [begin, end) set to disparity d and colour c.
void Paint(Layout& layout, int begin, int end, float d, const cv::Vec3f& c) {
  for (int x = begin; x < end; ++x) {
    layout.disparity[static_cast<std::size_t>(x)] = d;
    layout.colour[static_cast<std::size_t>(x)] = c;
  }
}

TEST(OcclusionAlternatives, AThinStructureInFrontKeepsItsDisparity) {
  Layout layout = Background();
  Paint(layout, 7, 9, 1.0f, kRed);  // a 2 px picket
  Scene scene(layout);
  const int refused = scene.Admit();
  EXPECT_EQ(scene.Preferred(7), 2);
  EXPECT_EQ(scene.Preferred(8), 2);
  EXPECT_EQ(refused, 2 * 2 * kHeight);  // both patches, both columns, every row
  EXPECT_EQ(scene.Preferred(3), 0);     // the background's patches are admitted
}

// The same picket lying flat (a rail): the check walks across the edge, here along y. An edge normal a quarter
// turn off would walk along the rail and find no surface behind within the 3 px wide image.
TEST(OcclusionAlternatives, AThinRailInFrontKeepsItsDisparity) {
  Layout layout = Background();
  Paint(layout, 7, 9, 1.0f, kRed);
  Scene scene(layout, Orientation::kRows);
  EXPECT_EQ(scene.Admit(), 2 * 2 * scene.width);  // both patches, both rows of the rail, every column
  EXPECT_EQ(scene.Preferred(7), 2);
  EXPECT_EQ(scene.Preferred(8), 2);
  EXPECT_EQ(scene.Preferred(3), 0);
}

// A slanted picket (positions 7 and 8: x + y from 14 to 17, about 3 px across). An edge normal mirrored in y, (1, -1)
// instead of (1, 1), would walk along it.
TEST(OcclusionAlternatives, ASlantedPicketInFrontKeepsItsDisparity) {
  Layout layout = Background();
  Paint(layout, 7, 9, 1.0f, kRed);
  Scene scene(layout, Orientation::kDiagonal);
  // Both patches of the picket's 60 pixels but the 10 whose walk leaves the image before it meets the background.
  EXPECT_EQ(scene.Admit(), 2 * 50);
  for (const auto& [x, y] : {std::pair{7, 7}, std::pair{8, 8}, std::pair{9, 6}, std::pair{6, 10}})
    EXPECT_EQ(scene.PreferredAt(x, y), 2) << "(" << x << ", " << y << ")";
  EXPECT_EQ(scene.PreferredAt(3, 3), 0);
  EXPECT_EQ(scene.PreferredAt(12, 12), 0);
}

TEST(OcclusionAlternatives, WithoutTheCheckEveryPatchIsAdmitted) {
  Layout layout = Background();
  Paint(layout, 7, 9, 1.0f, kRed);
  Scene scene(layout);
  ThinStructureOptions off;
  off.reach = 0;
  EXPECT_EQ(scene.Admit(off), 0);
  EXPECT_EQ(scene.Preferred(7), 0);  // the picket is lost to the background
}

// A gap between two 2 px teeth reads as the teeth on the whole patch; the background beyond the teeth, within reach
// on both sides, has the gap's own colour, so the gap is not a structure in front: its partial patches stay.
TEST(OcclusionAlternatives, AGapBetweenTwoOccludersKeepsItsPatches) {
  Layout layout = Background();
  Paint(layout, 5, 11, 1.0f, kRed);
  Paint(layout, 7, 9, 1.0f, kGrey);  // the gap: background colour, read as the teeth
  Scene scene(layout);
  EXPECT_EQ(scene.Admit(), 0);
  EXPECT_EQ(scene.Preferred(7), 0);
  EXPECT_EQ(scene.Preferred(8), 0);
  // Blind to colour, the check would take the gap for a structure in front of the background beyond the teeth.
  ThinStructureOptions colour_blind;
  colour_blind.colour_difference = -1.0f;
  colour_blind.blend_difference = -1.0f;
  Scene blind(layout);
  EXPECT_GT(blind.Admit(colour_blind), 0);
}

// The mixed pixel on the edge between two tiles of a checker is a blend of the two tiles' colours, not a structure
// of its own, even where the whole patch reads it nearer than both.
TEST(OcclusionAlternatives, TheMixedPixelOfAColourEdgeIsNotAStructure) {
  const cv::Vec3f black(0.05f, 0.05f, 0.05f);
  const cv::Vec3f tan(0.65f, 0.55f, 0.35f);
  Layout layout = Background();
  Paint(layout, 0, 8, -1.0f, black);
  Paint(layout, 9, kWidth, -1.0f, tan);
  Paint(layout, 8, 9, 1.0f, 0.5f * (black + tan));
  Scene scene(layout);
  EXPECT_EQ(scene.Admit(), 0);
  EXPECT_EQ(scene.Preferred(8), 0);
  // The same pixel in a colour of its own is a 1 px structure in front.
  Paint(layout, 8, 9, 1.0f, kRed);
  Scene structure(layout);
  EXPECT_EQ(structure.Admit(), 2 * kHeight);
  EXPECT_EQ(structure.Preferred(8), 2);
}

// A structure wider than the reach is not thin: beside its edge, its own pixels see no surface behind on that side.
TEST(OcclusionAlternatives, AWideObjectIsNotAThinStructure) {
  Layout layout = Background();
  Paint(layout, 2, 14, 1.0f, kRed);
  Scene scene(layout);
  EXPECT_EQ(scene.Admit(), 0);
}

// A pixel at disparity d can be hidden only by a surface nearer than d by its distance over the longest view offset.
TEST(OccluderHorizon, FallsWithTheDistanceFromANearerSurface) {
  DisparityMap disparity(9, 9, 0.0f);
  disparity.at(4, 4) = 1.0f;
  const DisparityMap horizon = OccluderHorizon(disparity, 4.0, 0);
  EXPECT_FLOAT_EQ(horizon.at(4, 4), 1.0f);
  EXPECT_FLOAT_EQ(horizon.at(4, 6), 0.5f);                                          // 2 px straight
  EXPECT_NEAR(horizon.at(6, 6), 1.0f - 2.0f * std::numbers::sqrt2 / 4.0f, 1e-6);    // 2 px along the diagonal
  EXPECT_NEAR(horizon.at(5, 6), 1.0f - (1.0f + std::numbers::sqrt2) / 4.0f, 1e-6);  // chamfer: 2.41 px, not 2.24
  EXPECT_FLOAT_EQ(horizon.at(4, 8), 0.0f);  // 4 px: down to the background's own
  EXPECT_FLOAT_EQ(horizon.at(0, 0), 0.0f);  // beyond: the background
  // Widened by 1 px, the nearer surface covers its neighbours first.
  const DisparityMap widened = OccluderHorizon(disparity, 4.0, 1);
  EXPECT_FLOAT_EQ(widened.at(4, 5), 1.0f);
  EXPECT_FLOAT_EQ(widened.at(4, 7), 0.5f);
  EXPECT_THROW(OccluderHorizon(disparity, 0.0, 0), Error);
}

// On a flat background with nothing nearer around, a partial patch's dip at a nearer label is not an occlusion and
// is not admitted; a surface in front within reach lets the same dip in up to its horizon.
TEST(OcclusionAlternatives, APartialPatchStandsInOnlyBelowTheOccluderHorizon) {
  const auto dip_at = [](Scene& scene, int label) {
    for (int y = 0; y < scene.height; ++y)
      for (int x = 0; x < scene.width; ++x)
        for (int l = 0; l < 3; ++l) scene.alternatives.half.Curve(y, x)[l] = l == label ? 0.1f : 0.7f;
  };
  Scene alone(Background());
  dip_at(alone, 1);
  EXPECT_EQ(alone.Admit(), 0);
  EXPECT_EQ(alone.Preferred(9), 0);  // the whole patch's background
  // Without a horizon the dip wins, as the lower envelope always let it.
  OccluderHorizonOptions off;
  off.slack = -1.0f;
  Scene unlimited(Background());
  dip_at(unlimited, 1);
  unlimited.Admit({}, off);
  EXPECT_EQ(unlimited.Preferred(9), 1);

  // A wide surface in front at positions 0..4: position 9 lies 5 px from it, 3 px once widened by 2, so its horizon
  // is 1 - 3 / 5.66 = 0.47: the dip at 0 is admitted, one at 1 (the surface's own disparity) is not.
  Layout layout = Background();
  Paint(layout, 0, 5, 1.0f, kRed);
  Scene beside(layout);
  dip_at(beside, 1);
  beside.Admit();
  EXPECT_EQ(beside.Preferred(9), 1);
  Scene nearer(layout);
  dip_at(nearer, 2);
  nearer.Admit();
  EXPECT_EQ(nearer.Preferred(9), 0);
  EXPECT_EQ(nearer.Preferred(5), 2);  // beside the surface the horizon reaches its disparity
}

TEST(OcclusionAlternatives, VolumesOfAnotherShapeAreAnError) {
  Scene scene(Background());
  scene.alternatives.along = CostVolume();  // a volume of another shape (empty)
  EXPECT_THROW(scene.Admit(), Error);
}

}  // namespace
}  // namespace lfsp::depth
