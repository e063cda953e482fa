// The full method on light fields with known disparity: the shift-based occluder scene of this folder and the
// simulator's ideal renderings.

#include <gtest/gtest.h>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/depth/occlusion.h"
#include "lfsp/simulate/render.h"
#include "synthetic_light_field.h"

namespace lfsp::depth {
namespace {

MetricOptions SmallImageMetrics() {
  MetricOptions options;
  options.boundary = 8;  // the toolkit's 15 px of 512 scaled to ~100 px images would be 3; keep shifts' reach out
  return options;
}

DepthEvaluation EstimateAndScore(const LightField& light_field, const DisparityMap& gt, bool occlusion,
                                 bool regularise) {
  DepthOptions options;
  options.occlusion_handling = occlusion;
  options.regularise = regularise;
  const DepthResult result = EstimateDepth(light_field, options);
  EXPECT_EQ(result.disparity.width(), gt.width());
  EXPECT_EQ(result.confidence.width(), gt.width());
  return EvaluateDisparity(result.disparity, gt, SmallImageMetrics());
}

class ShiftSceneTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new testing::ShiftLightField(testing::MakeShiftLightField({})); }
  static void TearDownTestSuite() { delete scene_; }
  static testing::ShiftLightField* scene_;
};
testing::ShiftLightField* ShiftSceneTest::scene_ = nullptr;

TEST_F(ShiftSceneTest, FullMethodRecoversPlaneAndOccluder) {
  const DepthEvaluation e = EstimateAndScore(scene_->light_field, scene_->disparity, true, true);
  // Measured BadPix 0.07 0.19 %, MSE x100 0.019 (9x9x96x96, 8 px frame); the bounds leave room for harmless
  // changes (about 3x and 5x), not for a real regression (plain winner-take-all without occlusion handling: ~15 %
  // / ~60).
  EXPECT_LT(e.all.badpix_007, 0.6);
  EXPECT_LT(e.all.mse_x100, 0.1);
}

TEST_F(ShiftSceneTest, OcclusionHandlingHelpsNearTheOccluderEdge) {
  const DepthEvaluation with = EstimateAndScore(scene_->light_field, scene_->disparity, true, true);
  const DepthEvaluation without = EstimateAndScore(scene_->light_field, scene_->disparity, false, true);
  // Measured near the square's edge: BadPix 0.07 0.81 % with, 3.85 % without; MSE x100 0.04 with, 2.6 without
  // (without, before the wide median: 24.3 % and 93).
  EXPECT_LT(with.near_discontinuities.badpix_007, 0.75 * without.near_discontinuities.badpix_007);
  EXPECT_LT(with.near_discontinuities.mse_x100, 0.5 * without.near_discontinuities.mse_x100);
}

TEST_F(ShiftSceneTest, RegularisationBeatsWinnerTakeAll) {
  const DepthEvaluation full = EstimateAndScore(scene_->light_field, scene_->disparity, true, true);
  const DepthEvaluation wta = EstimateAndScore(scene_->light_field, scene_->disparity, true, false);
  EXPECT_LT(full.all.badpix_007, wta.all.badpix_007);
}

// A built-in scene rendered with views x views views of size x size, as a bundle (metadata with its disparity
// range, as depth reads it) beside the rendered truth.
struct RenderedScene {
  simulate::RenderedLightField rendered;
  Bundle bundle;
};
RenderedScene Render(const char* name, int views, int size) {
  simulate::RenderOptions render;
  render.nu = render.nv = views;
  render.width = render.height = size;
  const simulate::Scene scene = simulate::BuiltinScene(name);
  RenderedScene out{simulate::RenderLightField(scene, render), {}};
  out.bundle = simulate::ToBundle(out.rendered, scene);
  return out;
}

// The default method and a variant of it on one rendered scene: the default's result, and both scored against the
// rendered truth over the HCI frame.
struct Scored {
  DepthResult result;
  DepthEvaluation with;     // the default method
  DepthEvaluation without;  // the variant
};
Scored DefaultAgainstVariant(const RenderedScene& scene, const DepthOptions& variant) {
  Scored scored{EstimateDepth(scene.bundle.light_field, {}), {}, {}};
  scored.with = EvaluateDisparity(scored.result.disparity, scene.rendered.disparity);
  scored.without =
      EvaluateDisparity(EstimateDepth(scene.bundle.light_field, variant).disparity, scene.rendered.disparity);
  return scored;
}

TEST(SimulatedScene, OccludersSceneWithinBound) {
  const auto [rendered, bundle] = Render("occluders", 9, 128);
  const DepthResult result = EstimateDepth(bundle.light_field, {});
  const DepthEvaluation e = EvaluateDisparity(result.disparity, rendered.disparity, SmallImageMetrics());
  // Measured BadPix 0.07 9.1 %, MSE x100 3.9 on 9x9x128x128 (9.1 % and 3.8 before the occluder horizon; 9.7 % and
  // 5.1 before the wide median).
  EXPECT_LT(e.all.badpix_007, 11.0);
  EXPECT_LT(e.all.mse_x100, 5.0);
}

// Background next to an occluder is hidden in the outer views on the occluder's side as far as the largest shift
// between the centre and an outer view; matched on all views there, the occluder's edge, carried along with it,
// wins and the occluder grows. The automatic radius covers that band; half of it (the old rule) did not.
TEST(SimulatedScene, BackgroundBesideAnOccluderIsNotTakenByIt) {
  const auto [rendered, bundle] = Render("two-horses", 7, 256);
  const DepthResult automatic = EstimateDepth(bundle.light_field, {});
  DepthOptions half_band;
  half_band.occlusion.radius = 0.5 * AutomaticOcclusionRadius(7, 7, automatic.range.min, automatic.range.max);
  const DepthResult narrow = EstimateDepth(bundle.light_field, half_band);
  const DepthEvaluation with = EvaluateDisparity(automatic.disparity, rendered.disparity, SmallImageMetrics());
  const DepthEvaluation without = EvaluateDisparity(narrow.disparity, rendered.disparity, SmallImageMetrics());
  // Measured on 7x7x256x256: BadPix 0.07 0.98 %, MSE x100 1.23; with half the radius 2.70 % and 4.62 (before the
  // wide median 2.23 % and 3.98; with half the radius 4.84 % and 10.7).
  EXPECT_LT(with.all.badpix_007, 2.0);
  EXPECT_LT(with.all.mse_x100, 2.5);
  EXPECT_LT(with.all.mse_x100, 0.6 * without.all.mse_x100);
}

// A pixel in a 1-4 px gap between two teeth of the comb is hidden in the views on both sides of the half-patch
// split; only the views along the teeth see it. Without them the gaps read as the teeth.
TEST(SimulatedScene, GapsBetweenCombTeethReadAsTheBackground) {
  DepthOptions halves_only;
  halves_only.cost.along_edge_penalty = 0.0f;
  const auto [along, with, without] = DefaultAgainstVariant(Render("comb", 9, 512), halves_only);  // laid out for 512
  // Measured on 9x9x512x512: BadPix 0.07 1.12 %, MSE x100 1.23 (1.15 % and 1.24 before the occluder horizon, 1.49 %
  // and 2.36 before the wide median; 3.0 % and 7.3 when the views along the teeth came from the smoothed gradient);
  // with the halves only 10.5 % and 31.8.
  EXPECT_LT(with.all.badpix_007, 1.3);
  EXPECT_LT(with.all.mse_x100, 3.24);  // issue 19's anchor: SPO on HCI's stratified scene
  EXPECT_LT(with.all.mse_x100, 0.2 * without.all.mse_x100);
}

// The layers scene's 2 px pickets and 3 px rails stand in front of a fine checker. The partial angular patches
// near their edges prefer the checker's disparity (occlusion_alternatives.h); admitted everywhere, they took most of
// the pickets.
TEST(SimulatedScene, ThinStructuresInFrontKeepTheirDepth) {
  DepthOptions unchecked;
  unchecked.thin_structures.reach = 0;
  const auto [checked, with, without] = DefaultAgainstVariant(Render("layers", 9, 512), unchecked);  // laid out for 512
  // Measured on 9x9x512x512: BadPix 0.07 2.42 %, MSE x100 1.35 (2.43 % before the occluder horizon; 2.58 % and 1.95
  // before the wide median); every patch admitted: 4.30 % and 6.14 (before the wide median). (2.89 % and 2.56 when
  // its fine checker was taken for noise and the views presmoothed, presmooth.h.)
  EXPECT_LT(with.all.badpix_007, 2.55);  // issue 19's anchor: SPO on HCI's stratified scene
  EXPECT_LT(with.all.mse_x100, 3.24);    // issue 19's anchor: SPO on HCI's stratified scene
  EXPECT_LT(with.all.mse_x100, 0.5 * without.all.mse_x100);
  EXPECT_GT(checked.thin_structure_refusals, 0);
}

// The occluders scene's thin branches and bars cross a checker of flat squares. The semi-global pass spreads a
// bar's disparity over the flat square beside it (nothing in a flat patch tells the two apart), in blobs wider than
// the fine median's window. The occluder horizon keeps the half patches' dips at the bar's disparity out of the
// square (occlusion_alternatives.h), and the wide median takes back what still spreads (refinement.h).
TEST(SimulatedScene, AThinOccludersDisparityDoesNotSpreadOverAFlatRegionBesideIt) {
  DepthOptions fine_median_only;
  fine_median_only.median.wide_radius = 0;
  const auto [automatic, with, without] = DefaultAgainstVariant(Render("occluders", 9, 512), fine_median_only);
  // Measured on 9x9x512x512: BadPix 0.07 1.74 %, MSE x100 1.46 (2.25 % and 1.75 before the occluder horizon); with
  // the fine median only 2.27 % and 2.06 (3.50 % and 3.11 before the horizon).
  EXPECT_LT(with.all.badpix_007, 2.0);
  EXPECT_LT(with.all.mse_x100, 1.6);
  EXPECT_LT(with.all.badpix_007, 0.85 * without.all.badpix_007);
  EXPECT_LT(with.all.mse_x100, 0.8 * without.all.mse_x100);
}

}  // namespace
}  // namespace lfsp::depth
