// EstimateNoiseSigma: reads added white noise on a textured image, and reads a clean texture as (almost) noiseless.

#include "lfsp/core/noise.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

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

}  // namespace
}  // namespace lfsp
