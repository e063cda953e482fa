// The scenes of issue 43, which show depth's two faults on the benchmark: foreground fattening across occlusion edges
// (bars) and sub-pixel precision on smooth curved surfaces (sculpture). Each is rendered at the benchmark's 9 x 9 x
// 512 x 512 and scored with the region metrics. The bounds hold today's figures (BENCHMARKS.md, 2026-12-06) with a
// margin: a change that makes either fault worse fails here.

#include <gtest/gtest.h>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/depth/region_metrics.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::depth {
namespace {

struct Scored {
  simulate::RenderedLightField rendered;
  EvaluationMasks masks;
  DepthEvaluation evaluation;
};

Scored RenderAndScore(const char* scene) {
  simulate::RenderOptions options;
  options.width = options.height = 512;
  Scored scored{simulate::RenderLightField(simulate::BuiltinScene(scene), options), {}, {}};
  const DisparityMap& gt = scored.rendered.disparity;
  scored.masks = DeriveEvaluationMasks(gt, MetricOptions{});
  const DepthResult result = EstimateDepth(scored.rendered.light_field, {});
  scored.evaluation = EvaluateDisparity(result.disparity, gt, MetricOptions{}, scored.masks, &result.confidence);
  return scored;
}

TEST(OcclusionEdges, BarsOfEveryWidthStandInFrontOfEachWall) {
  const Scored bars = RenderAndScore("bars");
  const DisparityMap& gt = bars.rendered.disparity;
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
  const DepthEvaluation& e = bars.evaluation;
  EXPECT_LE(e.near_discontinuities.badpix_007, 5.5);  // 4.19 %
  EXPECT_LE(e.all.badpix_007, 2.2);                   // 1.54 %
  EXPECT_LE(e.fattening_near_discontinuities, 80.0);  // 65 %
  ASSERT_TRUE(e.sparsification.has_value());
  EXPECT_LT(e.sparsification->area, 0.1);  // 0.064, oracle 0.013 (0.113 before the edge term)
}

TEST(OcclusionEdges, SculptureHasSmoothSurfacesAndTheirRims) {
  const Scored sculpture = RenderAndScore("sculpture");
  const DepthEvaluation& e = sculpture.evaluation;
  EXPECT_GT(e.smooth_surface_pixels, 30000u);         // 47130 of the ellipsoids
  EXPECT_GT(e.plane_pixels, 100000u);                 // the wall
  EXPECT_LE(e.bumpiness_smooth_surfaces, 0.8);        // 0.53
  EXPECT_LE(e.near_discontinuities.badpix_007, 4.5);  // 3.24 %
  EXPECT_LE(e.all.mse_x100, 0.15);                    // 0.09
}

}  // namespace
}  // namespace lfsp::depth
