// The depth estimator's pre-smoothing: how much it chooses for a noise level, and what it buys on a noisy light field
// with known disparity. (The noise estimate itself is tested in tests/core/noise_test.cc.)

#include "lfsp/depth/presmooth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/simulate/image_noise.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::depth {
namespace {

TEST(NoiseEstimate, SmoothingGrowsWithNoiseAndIsCapped) {
  EXPECT_EQ(PresmoothSigmaForNoise(0.0019), 0.0);  // HCI antinous
  EXPECT_EQ(PresmoothSigmaForNoise(kDepthCleanNoise), 0.0);
  EXPECT_NEAR(PresmoothSigmaForNoise(0.004), 1.0, 1e-9);
  EXPECT_LT(PresmoothSigmaForNoise(0.0035), PresmoothSigmaForNoise(0.0045));
  EXPECT_EQ(PresmoothSigmaForNoise(0.5), 2.5);
}

double MeanAbsoluteError(const DisparityMap& a, const DisparityMap& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) sum += std::abs(a.at(y, x) - b.at(y, x));
  return sum / (a.width() * a.height());
}

TEST(Presmooth, AutomaticSmoothingRescuesDepthOnANoisyLightField) {
  simulate::RenderOptions render;
  render.width = render.height = 128;
  render.supersampling = 2;
  const simulate::RenderedLightField scene = simulate::RenderLightField(simulate::BuiltinScene("planes"), render);
  LightField noisy = scene.light_field;
  simulate::AddGaussianNoise(noisy, 0.06, 3);

  DepthOptions options;
  options.range = DisparityRange{-2.0f, 2.0f};
  const DepthResult automatic = EstimateDepth(noisy, options);
  options.presmooth_sigma = 0.0f;
  const DepthResult unsmoothed = EstimateDepth(noisy, options);
  const double error_automatic = MeanAbsoluteError(automatic.disparity, scene.disparity);
  const double error_unsmoothed = MeanAbsoluteError(unsmoothed.disparity, scene.disparity);
  std::printf("noise estimate %.4f -> smoothing %.2f px; mean |error| %.3f (unsmoothed %.3f)\n", automatic.noise_sigma,
              automatic.presmooth_sigma, error_automatic, error_unsmoothed);
  EXPECT_GT(automatic.presmooth_sigma, 0.5);
  EXPECT_LT(error_automatic, 0.7 * error_unsmoothed);

  DepthOptions defaults;
  defaults.range = DisparityRange{-2.0f, 2.0f};
  const DepthResult clean = EstimateDepth(scene.light_field, defaults);
  EXPECT_EQ(clean.presmooth_sigma, 0.0) << "noise estimate on the clean views: " << clean.noise_sigma;
}

}  // namespace
}  // namespace lfsp::depth
