// The depth estimator's automatic choices for noisy views (pre-smoothing, sampler, excluded ring) and what they buy on
// a noisy light field with known disparity. (The noise estimate itself is tested in tests/core/noise_test.cc.)

#include "lfsp/depth/presmooth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/depth/detail_weight.h"
#include "lfsp/simulate/image_noise.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::depth {
namespace {

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

// Noisy views (a lenslet decode, or noise above kDepthCleanNoise) are smoothed by kNoisyViewsPresmooth and
// resampled by the noise-matched kernel; clean rendered ones are neither. A decode leaves out ring 2 when 7x7 views
// remain, ring 1 with 5x5.
TEST(Presmooth, AutomaticChoicesFollowTheViewsNoiseAndSource) {
  LightField decoded(LightFieldShape{9, 9, 8, 8, 3});
  decoded.metadata["decode"] = {{"demosaic", "gradient"}};
  const LightField rendered(LightFieldShape{9, 9, 8, 8, 3});
  const double noisy = 0.02;
  EXPECT_EQ(AutomaticPresmoothSigma(rendered, 0.0019), 0.0) << "HCI antinous";
  EXPECT_EQ(AutomaticPresmoothSigma(rendered, kDepthCleanNoise), 0.0);
  EXPECT_EQ(AutomaticPresmoothSigma(rendered, noisy), kNoisyViewsPresmooth);
  EXPECT_EQ(AutomaticPresmoothSigma(decoded, 0.0), kNoisyViewsPresmooth) << "a decode is noisy at the pixel scale";
  EXPECT_EQ(AutomaticSampler(rendered, 0.0019), Sampler::kBilinear);
  EXPECT_EQ(AutomaticSampler(rendered, noisy), Sampler::kNoiseMatched);
  EXPECT_EQ(AutomaticSampler(decoded, 0.0), Sampler::kNoiseMatched);
  EXPECT_EQ(ExcludedRingFor(rendered), 0);
  EXPECT_EQ(ExcludedRingFor(decoded), 2);
  const auto ring_for = [&](int nu, int nv) {
    LightField central(LightFieldShape{nu, nv, 8, 8, 3});
    central.metadata = decoded.metadata;
    return ExcludedRingFor(central);
  };
  EXPECT_EQ(ring_for(7, 7), 2);
  EXPECT_EQ(ring_for(6, 6), 1);
  EXPECT_EQ(ring_for(5, 5), 1);
  EXPECT_EQ(ring_for(9, 5), 1) << "the smaller side decides";
  EXPECT_EQ(ring_for(4, 4), 0);
  EXPECT_EQ(ring_for(3, 3), 0);
}

// A noise-free view of a fine sharp texture (the layers scene's background: a checker of 8.2 px squares at 20
// degrees) reads as noisy by the median's estimate but clean by the lower quartile's. It is not smoothed (that
// would only blur the thin structures in front of it), and it is resampled by the noise-matched kernel: bilinear
// resampling, whose blur changes with the sub-pixel shift, reads such a checker about 0.04 px near.
TEST(Presmooth, AFineSharpTextureIsNotTakenForNoise) {
  const nlohmann::json checker = {
      {"type", "checker"}, {"colours", {{0.9, 0.9, 0.85}, {0.35, 0.4, 0.45}}}, {"period", 0.064}, {"angle", 20.0}};
  const nlohmann::json plane = {{"type", "plane"},
                                {"name", "background"},
                                {"label", 0},
                                {"disparity", -1.3},
                                {"shape", {{"type", "everywhere"}}},
                                {"texture", checker}};
  const nlohmann::json scene = {{"name", "checker"}, {"objects", nlohmann::json::array({plane})}};
  simulate::RenderOptions render;
  render.width = render.height = 128;  // 0.064 of 128: squares of 8.2 px
  render.nu = render.nv = 7;
  const simulate::RenderedLightField rendered = simulate::RenderLightField(simulate::SceneFromJson(scene), render);
  DepthOptions options;
  options.range = DisparityRange{-2.0f, 0.0f};
  const DepthResult automatic = EstimateDepth(rendered.light_field, options);
  EXPECT_GT(automatic.noise_sigma, kDepthCleanNoise) << "the median reads the checker's edges as noise";
  EXPECT_LT(automatic.noise_sigma_lower_quartile, kDepthCleanNoise);
  EXPECT_EQ(automatic.presmooth_sigma, 0.0);
  EXPECT_EQ(automatic.sampler, Sampler::kNoiseMatched);
  options.cost.sampler = Sampler::kBilinear;
  const DepthResult bilinear = EstimateDepth(rendered.light_field, options);
  const double error_automatic = MeanAbsoluteError(automatic.disparity, rendered.disparity);
  const double error_bilinear = MeanAbsoluteError(bilinear.disparity, rendered.disparity);
  std::printf("mean |error| %.4f noise-matched, %.4f bilinear\n", error_automatic, error_bilinear);
  EXPECT_LT(error_automatic, 0.5 * error_bilinear);
}

// The automatic detail weight: whole on unsmoothed views; on smoothed ones, low where the detail band holds little
// more than noise (a weak texture) and high where a strong texture survives the smoothing.
TEST(DetailWeight, FollowsTheDetailBandsSignalAgainstItsNoise) {
  const CostOptions options;
  cv::Mat weak(192, 192, CV_32FC3), strong(192, 192, CV_32FC3);
  cv::RNG random(5);
  random.fill(weak, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(weak, weak, cv::Size(0, 0), 4.0);
  weak = 0.5 + 0.3 * (weak - 0.5);  // faint blobs, as the two-horses background
  random.fill(strong, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(strong, strong, cv::Size(0, 0), 1.0);
  cv::Mat noise(weak.size(), weak.type());
  random.fill(noise, cv::RNG::NORMAL, 0.0, 0.008);
  const cv::Mat weak_noisy = weak + noise, strong_noisy = strong + noise;
  auto smoothed = [](const cv::Mat& view) {
    cv::Mat out;
    cv::GaussianBlur(view, out, cv::Size(0, 0), 2.5);
    return out;
  };
  EXPECT_EQ(DetailWeightFor(weak_noisy, weak_noisy, 0.0, true, 10.0, options), 1.0f)
      << "unsmoothed views keep the whole term";
  EXPECT_EQ(DetailWeightFor(weak_noisy, smoothed(weak_noisy), 2.5, false, 1.0, options), 1.0f)
      << "white noise on a rendered light field keeps the whole term";
  EXPECT_EQ(DetailWeightFor(strong_noisy, smoothed(strong_noisy), 2.5, true, 2.6, options), 0.0f)
      << "a decode whose finest band is mostly its own error leaves the term out";
  const float weak_weight = DetailWeightFor(weak_noisy, smoothed(weak_noisy), 2.5, true, 10.0, options);
  const float strong_weight = DetailWeightFor(strong_noisy, smoothed(strong_noisy), 2.5, true, 10.0, options);
  std::printf("detail weight: faint texture %.3f, strong texture %.3f\n", weak_weight, strong_weight);
  EXPECT_LT(weak_weight, 0.1f);
  EXPECT_GT(strong_weight, 0.5f);
}

// The colour term's channel weights follow each channel's noise: a decode's colour matrix leaves red and blue several
// times noisier than green, and their even sum let them decide weak textures (F01 two-horses capture, pipeline
// BadPix 0.07 36.7 -> 17.1 %).
TEST(ChannelWeights, FollowEachChannelsNoise) {
  cv::Mat texture(160, 160, CV_32FC3);
  cv::RNG random(9);
  random.fill(texture, cv::RNG::UNIFORM, 0.3, 0.7);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 3.0);
  const std::array<float, 3> clean = ChannelWeightsForNoise(EstimateNoiseSigmaPerChannel(texture));
  EXPECT_EQ(clean, (std::array<float, 3>{1.0f, 1.0f, 1.0f})) << "clean views weigh the channels evenly";
  std::vector<cv::Mat> channels;
  cv::split(texture, channels);
  const double sigma[3] = {0.012, 0.004, 0.016};
  for (int c = 0; c < 3; ++c) {
    cv::Mat noise(channels[c].size(), CV_32F);
    random.fill(noise, cv::RNG::NORMAL, 0.0, sigma[c]);
    channels[c] += noise;
  }
  cv::Mat noisy;
  cv::merge(channels, noisy);
  const std::array<float, 3> weights = ChannelWeightsForNoise(EstimateNoiseSigmaPerChannel(noisy));
  std::printf("channel weights for noise 0.012, 0.004, 0.016: %.2f %.2f %.2f\n", weights[0], weights[1], weights[2]);
  EXPECT_NEAR(weights[0] + weights[1] + weights[2], 3.0f, 1e-4f);
  // Inverse-variance weights: 3 / (1/0.012^2 + 1/0.004^2 + 1/0.016^2) times 1/sigma^2 = 0.28, 2.56, 0.16.
  EXPECT_NEAR(weights[0], 0.28f, 0.06f);
  EXPECT_NEAR(weights[1], 2.56f, 0.12f);
  EXPECT_NEAR(weights[2], 0.16f, 0.04f);
}

}  // namespace
}  // namespace lfsp::depth
