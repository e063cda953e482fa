// The noise estimate that drives the depth estimator's pre-smoothing, and what the smoothing buys on a noisy light
// field with known disparity.

#include "lfsp/depth/presmooth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/depth/metrics.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::depth {
namespace {

// A smooth random texture (blurred uniform noise, stretched to a contrast of about 0.5) in [0, 1].
cv::Mat Texture(int size, std::uint64_t seed) {
  cv::Mat texture(size, size, CV_32FC3);
  cv::RNG random(seed);
  random.fill(texture, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::normalize(texture, texture, 0.25, 0.75, cv::NORM_MINMAX);
  return texture;
}

cv::Mat WithNoise(const cv::Mat& image, double sigma, std::uint64_t seed) {
  cv::Mat noise(image.size(), image.type());
  cv::RNG random(seed);
  random.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  return image + noise;
}

TEST(NoiseEstimate, ReadsTheAddedNoiseOnATexturedImage) {
  const cv::Mat clean = Texture(256, 1);
  EXPECT_LT(EstimateNoiseSigma(clean), kNoiseFloor) << "a clean texture is not noise";
  for (double sigma : {0.01, 0.03, 0.06}) {
    // Grey noise: the estimate is made on the grey version, where independent RGB noise would shrink.
    cv::Mat grey;
    cv::cvtColor(clean, grey, cv::COLOR_RGB2GRAY);
    const double estimate = EstimateNoiseSigma(WithNoise(grey, sigma, 7));
    EXPECT_NEAR(estimate, sigma, 0.15 * sigma) << "sigma " << sigma;
  }
}

TEST(NoiseEstimate, SmoothingGrowsWithNoiseAndIsCapped) {
  EXPECT_EQ(PresmoothSigmaForNoise(0.002), 0.0);
  EXPECT_EQ(PresmoothSigmaForNoise(kNoiseFloor), 0.0);
  EXPECT_NEAR(PresmoothSigmaForNoise(0.014), 1.0, 1e-9);
  EXPECT_LT(PresmoothSigmaForNoise(0.01), PresmoothSigmaForNoise(0.02));
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
  cv::Mat all(1, static_cast<int>(noisy.size()), CV_32FC1, noisy.data());
  cv::Mat noise(all.size(), CV_32FC1);
  cv::RNG(3).fill(noise, cv::RNG::NORMAL, 0.0, 0.06);
  all += noise;

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

  const DepthResult clean = EstimateDepth(scene.light_field, DepthOptions{.range = DisparityRange{-2.0f, 2.0f}});
  EXPECT_EQ(clean.presmooth_sigma, 0.0) << "noise estimate on the clean views: " << clean.noise_sigma;
}

}  // namespace
}  // namespace lfsp::depth
