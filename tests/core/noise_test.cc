// EstimateNoiseSigma: reads added white noise on a textured image, and reads a clean texture as (almost) noiseless.

#include "lfsp/core/noise.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/simulate/texture.h"

namespace lfsp {
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
  EXPECT_LT(EstimateNoiseSigma(clean), 0.004) << "a clean texture is not noise";
  for (double sigma : {0.01, 0.03, 0.06}) {
    // Grey noise: the estimate is made on the grey version, where independent RGB noise would shrink.
    cv::Mat grey;
    cv::cvtColor(clean, grey, cv::COLOR_RGB2GRAY);
    const double estimate = EstimateNoiseSigma(WithNoise(grey, sigma, 7));
    EXPECT_NEAR(estimate, sigma, 0.15 * sigma) << "sigma " << sigma;
  }
}

// Pixel-scale texture everywhere (the bundled mini-Illum decode's case): the plain median reads the texture as noise,
// the floor of the flattest blocks does not, and on a texture with flat parts both read white noise right.
TEST(NoiseFloor, ReadsNoiseUnderATextureThatCoversTheView) {
  cv::Mat fine(128, 128, CV_32FC1);
  cv::RNG random(3);
  random.fill(fine, cv::RNG::UNIFORM, 0.1, 0.9);
  cv::GaussianBlur(fine, fine, cv::Size(0, 0), 0.6);
  // Flat in the top quarter of the rows, fine texture below.
  fine(cv::Rect(0, 0, 128, 32)).setTo(0.5);
  const double sigma = 0.01;
  const cv::Mat noisy = WithNoise(fine, sigma, 11);
  EXPECT_GT(EstimateNoiseSigma(noisy), 2.0 * sigma) << "the median reads the texture";
  EXPECT_NEAR(EstimateNoiseFloor(noisy), sigma, 0.15 * sigma);

  cv::Mat grey;
  cv::cvtColor(Texture(256, 5), grey, cv::COLOR_RGB2GRAY);
  for (double level : {0.005, 0.03}) {
    const cv::Mat textured = WithNoise(grey, level, 13);
    EXPECT_NEAR(EstimateNoiseFloor(textured), level, 0.15 * level) << "sigma " << level;
    EXPECT_NEAR(EstimateNoiseFloor(textured), EstimateNoiseSigma(textured), 0.15 * level);
  }
}

// The simulator's checker texture as the layers scene's background has it (8.2 px squares at 20 degrees), each
// pixel the average of 4 x 4 points: noise-free, yet edges lie under more than half of its pixels.
cv::Mat SharpChecker(int size) {
  constexpr int kSamples = 4;
  simulate::Texture texture;
  texture.kind = simulate::Texture::Kind::kChecker;
  texture.colour_a = {0.90f, 0.90f, 0.85f};
  texture.colour_b = {0.35f, 0.40f, 0.45f};
  texture.period = 8.2f / static_cast<float>(size);  // normalised units
  texture.angle = static_cast<float>(20.0 * CV_PI / 180.0);
  cv::Mat checker(size, size, CV_32FC3, cv::Scalar::all(0.0));
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i) {
          const simulate::Rgb rgb = texture.Evaluate((x + (i + 0.5f) / kSamples) / static_cast<float>(size),
                                                     (y + (j + 0.5f) / kSamples) / static_cast<float>(size));
          checker.at<cv::Vec3f>(y, x) += cv::Vec3f(rgb[0], rgb[1], rgb[2]) / (kSamples * kSamples);
        }
  return checker;
}

// The lower quartile reads a fine sharp texture's edges as texture, where the median reads them as noise; on white
// noise over a smooth texture both read the noise.
TEST(NoiseLowerQuartile, ReadsAFineSharpTextureAsClean) {
  const cv::Mat checker = SharpChecker(256);
  EXPECT_GT(EstimateChannelNoiseSigma(checker), 0.01) << "the median reads the checker's edges as noise";
  EXPECT_LT(EstimateChannelNoiseSigmaLowerQuartile(checker), 0.001);
  for (double sigma : {0.005, 0.03}) {
    const cv::Mat noisy = WithNoise(Texture(256, 9), sigma, 17);
    EXPECT_NEAR(EstimateChannelNoiseSigmaLowerQuartile(noisy), sigma, 0.15 * sigma) << "sigma " << sigma;
    EXPECT_NEAR(EstimateChannelNoiseSigmaLowerQuartile(noisy), EstimateChannelNoiseSigma(noisy), 0.1 * sigma);
  }
  // Over the checker, noise is read high (the texture adds to it), never low: noisy views never pass for clean.
  const cv::Mat noisy_checker = WithNoise(checker, 0.03, 19);
  EXPECT_GT(EstimateChannelNoiseSigmaLowerQuartile(noisy_checker), 0.85 * 0.03);
}

}  // namespace
}  // namespace lfsp
