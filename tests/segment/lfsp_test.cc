// LFSP on small synthetic light fields with ground truth known by construction: the simulator's scenes (planes,
// occluders, textures, exact per-ray labels) and a hand-made shift-based scene (two textured fronto-parallel planes).
// Sizes are small so the suite stays fast, except for the comb and layers, laid out for 512 x 512 views (about 20 s
// together); the other full-size checks are bench cases (bench/segment_bench.cc).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <set>

#include "lfsp/core/error.h"
#include "lfsp/segment/baselines.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "lfsp/simulate/render.h"

namespace lfsp::segment {
namespace {

simulate::RenderedLightField Render(const std::string& scene, int size, int views = 9) {
  simulate::RenderOptions options;
  options.nu = options.nv = views;
  options.width = options.height = size;
  return simulate::RenderLightField(simulate::BuiltinScene(scene), options);
}

// The largest number of 4-connected pieces any label has in the given view.
int MostPiecesOfALabel(const Labels& labels, ViewIndex view_index) {
  const cv::Mat view = labels.View(view_index);
  std::set<int> seen(view.begin<int>(), view.end<int>());
  int most = 0;
  for (int k : seen) {
    cv::Mat mask = view == k, components;
    most = std::max(most, cv::connectedComponents(mask, components, 4) - 1);  // minus the background
  }
  return most;
}

// Is each label one 4-connected piece in the centre view (where slices are connected by construction)?
bool EveryLabelConnectedInTheCentreView(const Labels& labels) {
  return MostPiecesOfALabel(labels, labels.shape().Centre()) == 1;
}

TEST(Lfsp, ProjectionAloneIsFullSlicedAndViewConsistent) {
  const simulate::RenderedLightField scene = Render("planes", 128);
  LfspParams params;
  params.size = 16;
  params.iterations = 0;
  const LfspResult result = SegmentLightField(scene.light_field, scene.disparity, params);
  EXPECT_EQ(EffectiveLabelRatio(result.labels), 1.0);
  EXPECT_EQ(LabelCount(result.labels), result.superpixels);
  for (std::size_t i = 0; i < result.labels.size(); ++i) ASSERT_GE(result.labels.data()[i], 0);
  // Observed 0.96 px (in frame: rays of every view projected back inside the centre frame); per-view SLIC
  // superpixels followed across views score about 3 px on these scenes.
  const double ss = SelfSimilarity(result.labels, scene.view_disparity, true);
  std::cout << "projection only: SS in frame " << ss << "\n";
  EXPECT_LT(ss, 1.2);
}

// A thin bar in front cuts a background superpixel in two in the side views where it passes over it. Both pieces
// are the same surface patch, so both keep the label (a per-view connectivity clean-up used to merge the smaller
// piece into a neighbour, which broke view consistency exactly next to thin occluders).
TEST(Lfsp, ASuperpixelCutByAThinOccluderKeepsBothPieces) {
  const simulate::RenderedLightField scene = Render("occluders", 128);
  LfspParams params;
  params.size = 16;
  const LfspResult result = SegmentLightField(scene.light_field, scene.disparity, params);
  int most = 0;
  for (int cam = 0; cam < static_cast<int>(result.labels.shape().Views()); ++cam)
    most = std::max(most, MostPiecesOfALabel(result.labels, ViewFromCameraNumber(cam, result.labels.shape().nu)));
  EXPECT_GE(most, 2);
  EXPECT_TRUE(EveryLabelConnectedInTheCentreView(result.labels));
  // Measured at this small size: SS 1.031 px against the carried reference's 0.939 (2.021 before the centre labels
  // were carried into the side views after the refinement, 2.054 with the clean-up). At 512 px (the bench) 0.798
  // against 0.807 (0.845 before the carry, 0.898 with the clean-up).
  const Labels reference = CarryCentreLabels(result.labels, scene.disparity, scene.view_disparity);
  const double ss = SelfSimilarity(result.labels, scene.view_disparity);
  const double ss_reference = SelfSimilarity(reference, scene.view_disparity);
  std::cout << "occluders 128: SS " << ss << " reference " << ss_reference << "\n";
  EXPECT_LT(ss - ss_reference, 0.25);
}

TEST(Lfsp, BlockCoordinateDescentImprovesBoundariesAndKeepsTheLightFieldProperties) {
  const simulate::RenderedLightField scene = Render("planes", 128);
  LfspParams params;
  params.size = 16;
  LfspParams initial = params;
  initial.iterations = 0;
  const LfspResult before = SegmentLightField(scene.light_field, scene.disparity, initial);
  const LfspResult after = SegmentLightField(scene.light_field, scene.disparity, params);
  const double ue_before = UndersegmentationError(before.labels, scene.labels);
  const double ue_after = UndersegmentationError(after.labels, scene.labels);
  const double br_before = BoundaryRecall(before.labels, scene.labels);
  const double br_after = BoundaryRecall(after.labels, scene.labels);
  std::cout << "UE " << ue_before << " -> " << ue_after << ", BR " << br_before << " -> " << br_after << ", moves "
            << after.label_moves << "\n";
  EXPECT_GT(after.label_moves, 0);
  EXPECT_LT(ue_after, 0.5 * ue_before);  // observed 0.117 -> 0.021
  EXPECT_GT(br_after, br_before);
  EXPECT_EQ(EffectiveLabelRatio(after.labels), 1.0);
  EXPECT_TRUE(EveryLabelConnectedInTheCentreView(after.labels));
  ASSERT_EQ(after.planes.size(), static_cast<std::size_t>(after.superpixels));
}

// The refinement runs the views of one angular phase in parallel, a band of rows at a time. Which thread takes which
// view and band must not matter: each view reads and writes only its own labels and those of other phases' views,
// and its bands run in order. A race there (two bands of one view at once) once changed the move count from run to
// run; a thread count that reorders the work would show it here.
TEST(Lfsp, TheLabelsDoNotDependOnTheNumberOfThreads) {
  const simulate::RenderedLightField scene = Render("occluders", 128);
  LfspParams params;
  params.size = 16;
  params.threads = 1;
  const LfspResult one = SegmentLightField(scene.light_field, scene.disparity, params);
  ASSERT_GT(one.label_moves, 0);
  for (const int threads : {2, 3}) {
    params.threads = threads;
    const LfspResult more = SegmentLightField(scene.light_field, scene.disparity, params);
    EXPECT_EQ(more.label_moves, one.label_moves) << threads << " threads";
    EXPECT_EQ(more.moves_per_iteration, one.moves_per_iteration) << threads << " threads";
    ASSERT_EQ(more.labels.size(), one.labels.size());
    EXPECT_TRUE(std::equal(one.labels.data(), one.labels.data() + one.labels.size(), more.labels.data()))
        << threads << " threads";
  }
}

TEST(Lfsp, MoreViewConsistentThanPerViewSlicWithComparableBoundaries) {
  for (const char* name : {"two-horses", "spheres"}) {
    const simulate::RenderedLightField scene = Render(name, 128);
    LfspParams params;
    params.size = 16;
    const LfspResult lfsp = SegmentLightField(scene.light_field, scene.disparity, params);
    BaselineParams baseline;
    baseline.size = 16;
    const Labels slic = SlicPerView(scene.light_field, baseline);
    const double ss_lfsp = SelfSimilarity(lfsp.labels, scene.view_disparity);
    const double ss_slic = SelfSimilarity(FollowToCentre(slic, scene.view_disparity), scene.view_disparity);
    const double br_lfsp = BoundaryRecall(lfsp.labels, scene.labels), br_slic = BoundaryRecall(slic, scene.labels);
    const double ue_lfsp = UndersegmentationError(lfsp.labels, scene.labels);
    const double ue_slic = UndersegmentationError(slic, scene.labels);
    std::cout << name << ": SS " << ss_lfsp << " vs SLIC " << ss_slic << ", BR " << br_lfsp << " vs " << br_slic
              << ", UE " << ue_lfsp << " vs " << ue_slic << "\n";
    EXPECT_LT(ss_lfsp, 0.5 * ss_slic) << name;  // observed 1.2 vs 2.9-3.3 px at this small size
    EXPECT_GT(br_lfsp, br_slic - 0.02) << name;
    EXPECT_LT(ue_lfsp, ue_slic + 0.002) << name;
    EXPECT_EQ(EffectiveLabelRatio(lfsp.labels), 1.0) << name;
  }
}

// Issue 19: next to thin occluders (a comb of 1-4 px teeth and gaps; several occlusion layers) the side views are as
// consistent as the centre labels carried by the ground truth, at the full 512 x 512 the comb is laid out for. Before
// the centre labels were carried into the side views after the refinement (centre_carry.h), SS was 1.46 (comb) and
// 2.38 px (layers) against references of 0.77 and 1.11, with BR 0.787 and 0.926; measured after: SS 0.650 and 1.098,
// BR 0.816 and 0.956 (BENCHMARKS.md, twentieth session).
TEST(Lfsp, AsConsistentAsTheCarriedReferenceNextToThinOccluders) {
  struct Expected {
    const char* scene;
    double min_boundary_recall;
  };
  for (const Expected& expected : {Expected{"comb", 0.80}, Expected{"layers", 0.94}}) {
    const simulate::RenderedLightField scene = Render(expected.scene, 512);
    const LfspResult result = SegmentLightField(scene.light_field, scene.disparity, {});
    const double ss = SelfSimilarity(result.labels, scene.view_disparity);
    const double ss_reference =
        SelfSimilarity(CarryCentreLabels(result.labels, scene.disparity, scene.view_disparity), scene.view_disparity);
    const double br = BoundaryRecall(result.labels, scene.labels);
    std::cout << expected.scene << ": SS " << ss << " reference " << ss_reference << " BR " << br << "\n";
    EXPECT_LE(ss, ss_reference + 0.03) << expected.scene;
    EXPECT_GE(br, expected.min_boundary_recall) << expected.scene;
    EXPECT_EQ(EffectiveLabelRatio(result.labels), 1.0) << expected.scene;
    EXPECT_TRUE(EveryLabelConnectedInTheCentreView(result.labels)) << expected.scene;
  }
}

// A hand-made light field: a textured background plane at disparity -1 and a textured square at +1.5 in front of it,
// rendered by shifting (the docs/DESIGN.md convention), with the object label of every ray.
struct ShiftScene {
  LightField light_field;
  Labels labels;
  DisparityMap disparity;
};

ShiftScene MakeShiftScene(int views, int size) {
  const LightFieldShape shape{views, views, size, size, 3};
  ShiftScene scene{LightField(shape), Labels(shape), DisparityMap(size, size)};
  const ViewIndex centre = shape.Centre();
  const float background_d = -1.0f, square_d = 1.5f;
  const float lo = size * 0.3f, hi = size * 0.7f;
  auto texture = [](float x, float y, bool square) {
    const float a = 0.5f + 0.25f * std::sin(0.7f * x) * std::cos(0.5f * y);
    return square ? cv::Vec3f(0.9f, 0.3f * a, 0.2f) : cv::Vec3f(0.2f * a, 0.4f + 0.3f * a, 0.8f);
  };
  for (int v = 0; v < views; ++v) {
    for (int u = 0; u < views; ++u) {
      const ViewIndex view{u, v};
      const float du = static_cast<float>(u - centre.u), dv = static_cast<float>(v - centre.v);
      for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
          // The ray meets the square plane at centre position (x + du d, y + dv d).
          const float sx = x + du * square_d, sy = y + dv * square_d;
          const bool square = sx >= lo && sx < hi && sy >= lo && sy < hi;
          const float d = square ? square_d : background_d;
          const cv::Vec3f colour = texture(x + du * d, y + dv * d, square);
          for (int c = 0; c < 3; ++c) scene.light_field.at(view, y, x, c) = colour[c];
          scene.labels.at(view, y, x) = square ? 1 : 0;
          if (view == centre) scene.disparity.at(y, x) = d;
        }
      }
    }
  }
  return scene;
}

TEST(Lfsp, FollowsTheObjectsOfAShiftedTwoPlaneScene) {
  const ShiftScene scene = MakeShiftScene(5, 64);
  LfspParams params;
  params.size = 10;
  const LfspResult result = SegmentLightField(scene.light_field, scene.disparity, params);
  const double asa = AchievableSegmentationAccuracy(result.labels, scene.labels);
  const double br = BoundaryRecall(result.labels, scene.labels);
  std::cout << "shift scene: ASA " << asa << " BR " << br << "\n";
  EXPECT_GT(asa, 0.995);
  EXPECT_GT(br, 0.95);
  EXPECT_EQ(EffectiveLabelRatio(result.labels), 1.0);
  EXPECT_TRUE(EveryLabelConnectedInTheCentreView(result.labels));
}

TEST(Lfsp, RejectsBadInput) {
  const ShiftScene scene = MakeShiftScene(3, 32);
  EXPECT_THROW(SegmentLightField(scene.light_field, DisparityMap(31, 32), {}), Error);
  LfspParams bad;
  bad.size = 1;
  EXPECT_THROW(SegmentLightField(scene.light_field, scene.disparity, bad), Error);
  bad = {};
  bad.lambda_b = -1;
  EXPECT_THROW(SegmentLightField(scene.light_field, scene.disparity, bad), Error);
  EXPECT_THROW(ParamsFromJson(nlohmann::json{{"size", "big"}}), Error);
  EXPECT_THROW(SegmentLightField(LightField(), DisparityMap(), {}), Error);
}

TEST(Lfsp, ParametersRoundTripThroughJson) {
  LfspParams params;
  params.size = 25;
  params.pen_angular = 3.5;
  params.iterations = 4;
  const LfspParams back = ParamsFromJson(ToJson(params));
  EXPECT_EQ(back.size, 25);
  EXPECT_EQ(back.pen_angular, 3.5);
  EXPECT_EQ(back.iterations, 4);
  EXPECT_EQ(back.lambda_d, 50.0);  // Table II default kept
}

}  // namespace
}  // namespace lfsp::segment
