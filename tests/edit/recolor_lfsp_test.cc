// The "done means" end to end: light-field superpixels from the segment library (LFSP at its default size,
// with the scene's true disparity) on simulator scenes of 9x9 views of 256x256; the superpixels of one object are
// selected in the centre view only (by the object's centre-view mask); the recolour must then change, in every view,
// the object's ground-truth rays (intersection over union at least 0.95) and nothing outside the selected
// superpixels (exactly).
//
// What this measures is how well the LFSP labels of side views follow the object, including its rays the centre
// view does not see. Measured worst views: the red ball of "spheres" 0.989, the noise card of "planes" 0.984 and the
// striped card half hidden behind it 0.976. (On toy 96x96 views with 10 px superpixels the striped card falls to
// 0.88: a few superpixels then make up the whole visible part of the card.)

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/core.hpp>

#include "lfsp/edit/recolor.h"
#include "lfsp/edit/selection.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::edit {
namespace {

cv::Mat ChangedRays(const LightField& before, const LightField& after, ViewIndex view) {
  cv::Mat difference;
  cv::absdiff(before.View(view), after.View(view), difference);
  std::vector<cv::Mat> channels;
  cv::split(difference, channels);
  return (channels[0] > 0) | (channels[1] > 0) | (channels[2] > 0);
}

double IntersectionOverUnion(const cv::Mat& a, const cv::Mat& b) {
  const double union_count = cv::countNonZero(a | b);
  return union_count == 0 ? 1.0 : cv::countNonZero(a & b) / union_count;
}

constexpr double kMinimumIou = 0.95;  // in every view

struct Case {
  const char* scene;
  int object;
};

class RecolorWithLfspTest : public ::testing::TestWithParam<Case> {};

TEST_P(RecolorWithLfspTest, CentreViewSelectionRecoloursTheObjectInEveryView) {
  const Case c = GetParam();
  simulate::RenderOptions render;
  render.nu = render.nv = 9;
  render.width = render.height = 256;
  render.supersampling = 2;
  const simulate::RenderedLightField scene = simulate::RenderLightField(simulate::BuiltinScene(c.scene), render);
  const segment::LfspResult segmentation = segment::SegmentLightField(scene.light_field, scene.disparity, {});

  const ViewIndex centre = scene.light_field.shape().Centre();
  const cv::Mat object_in_centre = scene.labels.View(centre) == c.object;
  const std::vector<std::int32_t> selection = SelectByMask(segmentation.labels, object_in_centre);

  LightField edited = scene.light_field;
  RecolorOptions options;
  options.adjustment.hue_degrees = 120.0f;
  options.adjustment.value = 0.7f;  // every non-black ray changes
  Recolor(edited, segmentation.labels, selection, options);

  const LightFieldShape& shape = scene.light_field.shape();
  double worst = 1.0;
  double sum = 0.0;
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      const ViewIndex view{u, v};
      const cv::Mat changed = ChangedRays(scene.light_field, edited, view);
      const double iou = IntersectionOverUnion(changed, scene.labels.View(view) == c.object);
      worst = std::min(worst, iou);
      sum += iou;
      EXPECT_GE(iou, kMinimumIou) << c.scene << " object " << c.object << " view " << u << "," << v;
      const cv::Mat selected = EditStrength(segmentation.labels.View(view), selection, 0.0f) > 0.0f;
      EXPECT_EQ(cv::countNonZero(changed & ~selected), 0) << "view " << u << "," << v;
    }
  std::printf("%s object %d: %zu superpixels selected, IoU over views: worst %.4f, mean %.4f\n", c.scene, c.object,
              selection.size(), worst, sum / static_cast<double>(shape.Views()));
}

INSTANTIATE_TEST_SUITE_P(SimulatorScenes, RecolorWithLfspTest,
                         ::testing::Values(Case{"spheres", 2}, Case{"planes", 3}, Case{"planes", 2}));

}  // namespace
}  // namespace lfsp::edit
