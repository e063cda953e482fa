// The noise-matched resampling kernel: its moments and noise gain at every sub-pixel position, and what it is for:
// on a noisy light field, a plane whose views are shifted by whole pixels reads its true disparity, where bilinear
// resampling pushes it off.

#include "lfsp/depth/noise_matched_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "lfsp/depth/depth_estimator.h"
#include "lfsp/simulate/image_noise.h"
#include "synthetic_light_field.h"

namespace lfsp::depth {
namespace {

TEST(NoiseMatchedKernel, KeepsTheSumCentroidBlurAndNoiseGainAtEveryPosition) {
  for (int i = 0; i < 100; ++i) {
    const double a = i / 100.0;
    const std::array<float, 4> w = NoiseMatchedWeights(static_cast<float>(a));
    double sum = 0.0, first = 0.0, second = 0.0, gain = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double offset = (k - 1) - a;  // taps at -1, 0, 1, 2 from floor(x)
      sum += w[k];
      first += w[k] * offset;
      second += w[k] * offset * offset;
      gain += w[k] * w[k];
    }
    EXPECT_NEAR(sum, 1.0, 1e-6) << "a = " << a;
    EXPECT_NEAR(first, 0.0, 1e-6) << "a = " << a;
    EXPECT_NEAR(second, 1.0 / 3.0, 1e-6) << "a = " << a;
    EXPECT_NEAR(gain, kNoiseMatchedGain, 1e-6) << "a = " << a;
  }
  // The centre view's kernel blurs as much (second moment 1/3).
  const auto& c = kNoiseMatchedCentreKernel;
  EXPECT_NEAR(c[0] + c[1] + c[2], 1.0, 1e-6);
  EXPECT_NEAR(c[0] + c[2], 1.0 / 3.0, 1e-6);
}

// The median disparity of the background (outside the square and a margin around it) of a noisy shift scene whose
// background sits at d = -1, where every view's shift is a whole number of pixels.
double BackgroundMedian(const DepthResult& result, int size) {
  std::vector<float> values;
  for (int y = 4; y < size - 4; ++y)
    for (int x = 4; x < size - 4; ++x) {
      const bool near_square = x > size / 3 - 12 && x < 2 * size / 3 + 12 && y > size / 3 - 12 && y < 2 * size / 3 + 12;
      if (!near_square) values.push_back(result.disparity.at(y, x));
    }
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  return values[values.size() / 2];
}

TEST(NoiseMatchedKernel, NoiseDoesNotPullAPlaneOffWholePixelShifts) {
  testing::ShiftScene scene;
  scene.size = 128;
  scene.background_contrast = 0.1f;
  testing::ShiftLightField shifted = testing::MakeShiftLightField(scene);
  simulate::AddGaussianNoise(shifted.light_field, 0.01, 11);
  DepthOptions options;
  options.presmooth_sigma = 0.6f;
  options.cost.sampler = Sampler::kBilinear;
  const double bilinear = BackgroundMedian(EstimateDepth(shifted.light_field, options), scene.size);
  options.cost.sampler = Sampler::kNoiseMatched;
  const double matched = BackgroundMedian(EstimateDepth(shifted.light_field, options), scene.size);
  options.cost.sampler = Sampler::kAutomatic;
  const DepthResult automatic = EstimateDepth(shifted.light_field, options);
  std::printf("background at d = -1 reads %+.4f bilinear, %+.4f noise-matched\n", bilinear, matched);
  EXPECT_NEAR(matched, -1.0, 0.02);
  EXPECT_GT(std::abs(bilinear + 1.0), 0.05) << "the bias this kernel removes";
  EXPECT_EQ(automatic.sampler, Sampler::kNoiseMatched) << "noise " << automatic.noise_sigma;
}

}  // namespace
}  // namespace lfsp::depth
