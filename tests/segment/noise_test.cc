// LFSP on a noisy light field: the colours the energy compares are smoothed by an amount chosen from the estimated
// noise, so side-view labels keep following the projection instead of the noise.

#include <gtest/gtest.h>

#include <cstdio>

#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "lfsp/simulate/image_noise.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::segment {
namespace {

TEST(LfspUnderNoise, AutomaticColourSmoothingKeepsLabelsConsistent) {
  simulate::RenderOptions render;
  render.width = render.height = 192;
  render.supersampling = 2;
  const simulate::RenderedLightField scene = simulate::RenderLightField(simulate::BuiltinScene("planes"), render);
  LightField noisy = scene.light_field;
  simulate::AddGaussianNoise(noisy, 0.08, 11);

  const LfspResult clean = SegmentLightField(scene.light_field, scene.disparity, {});
  EXPECT_EQ(clean.presmooth, 0.0) << "clean views read noise " << clean.noise_sigma;
  const LfspResult automatic = SegmentLightField(noisy, scene.disparity, {});
  LfspParams off;
  off.presmooth = 0.0;
  const LfspResult unsmoothed = SegmentLightField(noisy, scene.disparity, off);

  const double ss_clean = SelfSimilarity(clean.labels, scene.view_disparity);
  const double ss_automatic = SelfSimilarity(automatic.labels, scene.view_disparity);
  const double ss_unsmoothed = SelfSimilarity(unsmoothed.labels, scene.view_disparity);
  const double ue_automatic = UndersegmentationError(automatic.labels, scene.labels);
  const double ue_unsmoothed = UndersegmentationError(unsmoothed.labels, scene.labels);
  std::printf("noise %.4f -> smoothing %.2f px; SS clean %.3f, noisy %.3f (unsmoothed %.3f); UE %.4f (%.4f)\n",
              automatic.noise_sigma, automatic.presmooth, ss_clean, ss_automatic, ss_unsmoothed, ue_automatic,
              ue_unsmoothed);
  EXPECT_GT(automatic.presmooth, 1.0);
  EXPECT_LT(ss_automatic, ss_clean + 0.2);
  // Measured 0.907 against 1.057 px. The carry of the centre labels into the side views (centre_carry.h) keeps even
  // the unsmoothed side views near the centre's superpixels, so smoothing gains less SS than it did before the carry
  // (this check was a 0.3 px gain); its main gain is now in the boundaries, the UE below (0.022 against 0.081).
  EXPECT_LT(ss_automatic, ss_unsmoothed - 0.08);
  EXPECT_LT(ue_automatic, 0.5 * ue_unsmoothed);
}

}  // namespace
}  // namespace lfsp::segment
