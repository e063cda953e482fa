// Which partial angular patches a pixel near an edge may use: refused on a thin structure in front of the disparity
// they prefer, admitted in a gap between two occluders and beside a single one.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
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

// A row layout: for each column, the whole patch's disparity and the centre view's colour.
struct Layout {
  std::vector<float> disparity;
  std::vector<cv::Vec3f> colour;
};

// Every pixel an occlusion candidate beside a vertical edge (normal along x). The whole patch prefers each pixel's
// disparity in `layout`; both partial patches prefer the background's.
struct Scene {
  explicit Scene(const Layout& layout)
      : cost(kWidth, kHeight, 3), whole_patch(kWidth, kHeight), centre(kHeight, kWidth, CV_32FC3) {
    occlusion.candidate = cv::Mat(kHeight, kWidth, CV_8U, cv::Scalar(255));
    occlusion.split = cv::Mat(kHeight, kWidth, CV_8U, cv::Scalar(0));
    occlusion.along = cv::Mat(kHeight, kWidth, CV_8U, cv::Scalar(AlongPairForEdgeNormal(0.0)));
    alternatives.half = CostVolume(kWidth, kHeight, 3, std::numeric_limits<float>::infinity());
    alternatives.along = CostVolume(kWidth, kHeight, 3, std::numeric_limits<float>::infinity());
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        const float d = layout.disparity[static_cast<std::size_t>(x)];
        whole_patch.at(y, x) = d;
        centre.at<cv::Vec3f>(y, x) = layout.colour[static_cast<std::size_t>(x)];
        for (int l = 0; l < 3; ++l) {
          cost.Curve(y, x)[l] = kDisparities[static_cast<std::size_t>(l)] == d ? 0.3f : 0.6f;
          alternatives.half.Curve(y, x)[l] = l == 0 ? 0.1f : 0.7f;
          alternatives.along.Curve(y, x)[l] = l == 0 ? 0.2f : 0.8f;
        }
      }
    }
  }
  // The label the pixel's curve now prefers.
  int Preferred(int x) const {
    const float* curve = cost.Curve(1, x);
    return static_cast<int>(std::min_element(curve, curve + 3) - curve);
  }
  int Admit(const ThinStructureOptions& options = {}) {
    return AdmitOcclusionAlternatives(cost, alternatives, whole_patch, kDisparities, occlusion, centre, options);
  }

  CostVolume cost;
  OcclusionAlternatives alternatives;
  DisparityMap whole_patch;
  cv::Mat centre;
  OcclusionMap occlusion;
};

// Every column grey background at -1.
Layout Background() { return {std::vector<float>(kWidth, -1.0f), std::vector<cv::Vec3f>(kWidth, kGrey)}; }

// Columns [begin, end) set to disparity d and colour c.
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

TEST(OcclusionAlternatives, VolumesOfAnotherShapeAreAnError) {
  Scene scene(Background());
  scene.alternatives.along = CostVolume();  // a volume of another shape (empty)
  EXPECT_THROW(scene.Admit(), Error);
}

}  // namespace
}  // namespace lfsp::depth
