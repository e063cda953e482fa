// The scenes of issue 43, which show depth's two faults on the benchmark: foreground fattening across occlusion edges
// (bars) and sub-pixel precision on smooth curved surfaces (sculpture). Each is rendered at the benchmark's 9 x 9 x
// 512 x 512 and scored with the region metrics. The bounds hold today's figures (BENCHMARKS.md, 2026-12-06) with a
// margin: a change that makes either fault worse fails here. The regions are the simulator's own (from each pixel's
// object and its geometry), as a scene folder written by `lfsp simulate` holds them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/depth/region_metrics.h"
#include "lfsp/simulate/evaluation_masks.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"
#include "test_support.h"

namespace lfsp::depth {
namespace {

struct Rendered {
  simulate::RenderedLightField rendered;
  EvaluationMasks masks;  // the simulator's regions
};

Rendered Render(const char* scene) {
  simulate::RenderOptions options;
  options.width = options.height = 512;
  Rendered r{simulate::RenderLightField(simulate::BuiltinScene(scene), options), {}};
  const simulate::SceneEvaluationMasks regions = simulate::EvaluationMasksOf(r.rendered, simulate::BuiltinScene(scene));
  const char* source = "the simulator's geometry";
  r.masks = {regions.discontinuities, regions.planes, regions.smooth_surfaces, source, source, source};
  return r;
}

struct Scored {
  DisparityMap disparity;
  DepthEvaluation evaluation;
};

Scored EstimateAndScore(const Rendered& r, const DepthOptions& options = {}) {
  const DepthResult result = EstimateDepth(r.rendered.light_field, options);
  return {result.disparity,
          EvaluateDisparity(result.disparity, r.rendered.disparity, MetricOptions{}, r.masks, &result.confidence)};
}

// The median over rows 40..469 of each column of the 4 px bar (at 0.40 px), less the truth: the largest.
double FourPixelBarOffset(const DisparityMap& gt, const DisparityMap& disparity) {
  int bar_begin = 0;
  for (int x = 0, run = 0; x < 512; ++x) {
    run = gt.at(240, x) > 0.0f ? run + 1 : 0;
    if (run == 4 && (x + 1 == 512 || gt.at(240, x + 1) <= 0.0f)) bar_begin = x - 3;
  }
  EXPECT_GT(bar_begin, 0);
  double worst = 0.0;
  for (int x = bar_begin; x < bar_begin + 4; ++x) {
    std::vector<float> column;
    for (int y = 40; y < 470; ++y) column.push_back(disparity.at(y, x));
    std::nth_element(column.begin(), column.begin() + column.size() / 2, column.end());
    worst = std::max(worst, std::abs(static_cast<double>(column[column.size() / 2] - gt.at(240, x))));
  }
  return worst;
}

TEST(OcclusionEdges, BarsOfEveryWidthStandInFrontOfEachWall) {
  const Rendered rendered = Render("bars");
  const DisparityMap& gt = rendered.rendered.disparity;
  // Along the middle of each wall, count the runs of bar pixels (disparity above every wall's) and their widths.
  for (const int row : {80, 240, 470}) {
    std::vector<int> widths;
    int run = 0;
    for (int x = 0; x < 512; ++x) {
      if (gt.at(row, x) > 0.0f) {
        ++run;
      } else if (run > 0) {
        widths.push_back(run);
        run = 0;
      }
    }
    EXPECT_EQ(widths, (std::vector<int>{1, 2, 3, 4, 6, 8, 12})) << "row " << row;
  }
  // Every jump of this scene is between two objects, so the simulator's discontinuities are exactly the ones
  // derived from the ground truth; and every surface is flat.
  const EvaluationMasks derived = DeriveEvaluationMasks(gt, MetricOptions{});
  EXPECT_EQ(cv::countNonZero(rendered.masks.discontinuities != derived.discontinuities), 0);
  EXPECT_EQ(cv::countNonZero(rendered.masks.smooth_surfaces), 0);
  const Scored bars = EstimateAndScore(rendered);
  const DepthEvaluation& e = bars.evaluation;
  EXPECT_LE(e.near_discontinuities.badpix_007, 4.0);  // 3.67 % (4.19 before the occluder horizon)
  EXPECT_LE(e.all.badpix_007, 1.45);                  // 1.35 % (1.54)
  EXPECT_LE(e.fattening_near_discontinuities, 62.0);  // 56 % (65)
  ASSERT_TRUE(e.sparsification.has_value());
  EXPECT_LT(e.sparsification->area, 0.1);  // 0.064, oracle 0.013 (0.113 before the edge term)
}

// Near an edge a half of the angular patch stands in only below the occluder horizon (occlusion_alternatives.h): the
// plain lower envelope of the two halves read the 4 px bar 0.05-0.07 px too near, a dip no occluder explains.
// CostOptions::halves_agree_labels >= 0 (a half only where the two halves disagree) reads it right too, but is not
// the default: on the camera decodes it spreads the foreground (cost_volume.h).
TEST(OcclusionEdges, TheOccluderHorizonKeepsThinBarsAtTheirDisparity) {
  const Rendered rendered = Render("bars");
  const DisparityMap& gt = rendered.rendered.disparity;
  DepthOptions no_horizon, agree;
  no_horizon.occluder_horizon.slack = -1.0f;
  agree.cost.halves_agree_labels = 3;
  const Scored horizon = EstimateAndScore(rendered), envelope = EstimateAndScore(rendered, no_horizon),
               halves = EstimateAndScore(rendered, agree);
  const double horizon_offset = FourPixelBarOffset(gt, horizon.disparity);
  const double envelope_offset = FourPixelBarOffset(gt, envelope.disparity);
  const double halves_offset = FourPixelBarOffset(gt, halves.disparity);
  RecordProperty("horizon_bar_offset", std::to_string(horizon_offset));
  RecordProperty("envelope_bar_offset", std::to_string(envelope_offset));
  RecordProperty("halves_bar_offset", std::to_string(halves_offset));
  std::printf("4 px bar offset: horizon %.4f, envelope %.4f, halves %.4f; halves BadPix %.2f, disc. %.2f\n",
              horizon_offset, envelope_offset, halves_offset, halves.evaluation.all.badpix_007,
              halves.evaluation.near_discontinuities.badpix_007);
  EXPECT_LT(horizon_offset, 0.03);   // 0.009
  EXPECT_GT(envelope_offset, 0.04);  // 0.05-0.07
  EXPECT_LE(horizon.evaluation.near_discontinuities.badpix_007,
            envelope.evaluation.near_discontinuities.badpix_007 - 0.3);  // 3.67 against 4.19 %
  EXPECT_LT(halves_offset, 0.03);                                        // 0.001
  EXPECT_LE(halves.evaluation.all.badpix_007, 1.3);                      // 1.02 %
  EXPECT_LE(halves.evaluation.near_discontinuities.badpix_007, 3.3);     // 2.77 %
}

TEST(OcclusionEdges, SculptureHasSmoothSurfacesAndTheirRims) {
  const Scored sculpture = EstimateAndScore(Render("sculpture"));
  const DepthEvaluation& e = sculpture.evaluation;
  EXPECT_GT(e.smooth_surface_pixels, 70000u);         // 78306 of the ellipsoids
  EXPECT_GT(e.plane_pixels, 120000u);                 // 138270 of the wall
  EXPECT_LE(e.bumpiness_smooth_surfaces, 0.55);       // 0.38
  EXPECT_LE(e.near_discontinuities.badpix_007, 4.5);  // 3.24 %
  EXPECT_LE(e.all.mse_x100, 0.15);                    // 0.09
}

// What `lfsp simulate --ideal-only` writes beside ideal.h5 is what `lfsp evaluate depth` reads back: the regions
// are disjoint, the ground truth's curved surfaces are never called planes (as the derived regions do with the
// flattest part of an ellipsoid), and the files hold the same pixels.
TEST(OcclusionEdges, SimulatorRegionsFollowTheGeometryAndRoundTripThroughFiles) {
  const simulate::Scene scene = simulate::BuiltinScene("sculpture");
  simulate::RenderOptions options;
  options.width = options.height = 128;
  options.supersampling = 1;
  const simulate::RenderedLightField rendered = simulate::RenderLightField(scene, options);
  const simulate::SceneEvaluationMasks masks = simulate::EvaluationMasksOf(rendered, scene);
  EXPECT_EQ(cv::countNonZero(masks.discontinuities & masks.planes), 0);
  EXPECT_EQ(cv::countNonZero(masks.discontinuities & masks.smooth_surfaces), 0);
  EXPECT_EQ(cv::countNonZero(masks.planes & masks.smooth_surfaces), 0);
  EXPECT_EQ(cv::countNonZero(masks.discontinuities | masks.planes | masks.smooth_surfaces), 128 * 128);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x) {
      const int object = rendered.centre_objects.at<std::int32_t>(y, x);
      const bool curved = object >= 0 && scene.objects[static_cast<std::size_t>(object)].geometry ==
                                             simulate::SceneObject::Geometry::kEllipsoid;
      if (curved) {
        ASSERT_EQ(masks.planes.at<unsigned char>(y, x), 0) << y << "," << x;
      }
    }
  EXPECT_GT(cv::countNonZero(masks.smooth_surfaces), 1000);

  const testing::TempDir temp;
  const std::filesystem::path& folder = temp.path();
  simulate::WriteEvaluationMasks(masks, folder);
  const EvaluationMasks read = ReadEvaluationMasks(folder, rendered.disparity, MetricOptions{});
  EXPECT_EQ(cv::countNonZero(read.discontinuities != masks.discontinuities), 0);
  EXPECT_EQ(cv::countNonZero(read.planes != masks.planes), 0);
  EXPECT_EQ(cv::countNonZero(read.smooth_surfaces != masks.smooth_surfaces), 0);
  EXPECT_EQ(read.planes_source, "file " + (folder / "mask_planes.png").string());
}

}  // namespace
}  // namespace lfsp::depth
