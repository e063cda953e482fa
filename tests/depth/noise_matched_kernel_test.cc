// The noise-matched resampling kernel: its moments and noise gain at every sub-pixel position, and what it is for:
// on a noisy light field, a plane whose views are shifted by whole pixels reads its true disparity, where bilinear
// resampling pushes it off.

#include "lfsp/depth/noise_matched_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "lfsp/depth/cost_volume.h"
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

// A view's channel c at integer pixel (x, y), taps beyond the border clamped to it (as the cost volume does).
float Clamped(const LightField& light_field, ViewIndex view, int x, int y, int c) {
  const LightFieldShape& shape = light_field.shape();
  return light_field.at(view, std::clamp(y, 0, shape.height - 1), std::clamp(x, 0, shape.width - 1), c);
}

// The sampler written out tap by tap, for comparison with the cost volume's vectorised, border-split loops.
float Sample(const LightField& light_field, ViewIndex view, float x, float y, int c, Sampler sampler) {
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const float ax = x - std::floor(x), ay = y - std::floor(y);
  if (sampler == Sampler::kBilinear) {
    return (1 - ax) * (1 - ay) * Clamped(light_field, view, ix, iy, c) +
           ax * (1 - ay) * Clamped(light_field, view, ix + 1, iy, c) +
           (1 - ax) * ay * Clamped(light_field, view, ix, iy + 1, c) +
           ax * ay * Clamped(light_field, view, ix + 1, iy + 1, c);
  }
  const auto weights = sampler == Sampler::kCubic ? CubicConvolutionWeights : NoiseMatchedWeights;
  const std::array<float, 4> wx = weights(ax), wy = weights(ay);
  float sum = 0.0f;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) sum += wx[i] * wy[j] * Clamped(light_field, view, ix - 1 + i, iy - 1 + j, c);
  return sum;
}

// The centre view as the sampler compares it: as it is (bilinear, cubic), or blurred by kNoiseMatchedCentreKernel.
float Centre(const LightField& light_field, int x, int y, int c, Sampler sampler) {
  const ViewIndex centre = light_field.shape().Centre();
  if (sampler != Sampler::kNoiseMatched) return light_field.at(centre, y, x, c);
  float sum = 0.0f;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      sum += kNoiseMatchedCentreKernel[i] * kNoiseMatchedCentreKernel[j] *
             Clamped(light_field, centre, x + i - 1, y + j - 1, c);
  return sum;
}

// Keys' cubic convolution reproduces quadratics: sum 1, centroid a, second moment about a 0, at every a; and it
// interpolates (1 at the tap it sits on at a = 0).
TEST(CubicConvolution, ReproducesQuadraticsAtEveryPosition) {
  for (int i = 0; i <= 100; ++i) {
    const double a = i / 100.0;
    const std::array<float, 4> w = CubicConvolutionWeights(static_cast<float>(a));
    double sum = 0.0, first = 0.0, second = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double offset = (k - 1) - a;
      sum += w[k];
      first += w[k] * offset;
      second += w[k] * offset * offset;
    }
    EXPECT_NEAR(sum, 1.0, 1e-6) << a;
    EXPECT_NEAR(first, 0.0, 1e-6) << a;
    EXPECT_NEAR(second, 0.0, 1e-6) << a;
  }
  const std::array<float, 4> at_tap = CubicConvolutionWeights(0.0f);
  EXPECT_EQ(at_tap, (std::array<float, 4>{0.0f, 1.0f, 0.0f, 0.0f}));
  // Keys' a = -1/2 at a quarter pixel (Lagrange's cubic, exact on quadratics too, has -0.0547 here).
  const std::array<float, 4> quarter = CubicConvolutionWeights(0.25f);
  EXPECT_NEAR(quarter[0], -0.0703125f, 1e-6f);
  EXPECT_NEAR(quarter[1], 0.8671875f, 1e-6f);
}

// All three samplers against the tap-by-tap version on a light field smaller than their footprint, at shifts many times
// its size in both directions and at fractions on either side of whole pixels: every border path is taken.
TEST(NoiseMatchedKernel, CostVolumeSamplesLikeTheTapByTapSampler) {
  LightField light_field(LightFieldShape{3, 3, 5, 3, 3});
  std::mt19937 random(4);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  for (std::size_t i = 0; i < light_field.size(); ++i) light_field.data()[i] = value(random);
  const std::vector<float> disparities = {-7.3f, -1.0f, 0.4f, 0.999f, 6.9f};
  CostOptions options;
  options.detail_sigma = 0.0f;  // colour alone, untruncated, so the cost is the plain sum of differences
  options.colour_truncation = 1e9f;
  options.channel_weights = {1.0f, 1.0f, 1.0f};
  options.excluded_ring = 0;
  const LightFieldShape& shape = light_field.shape();
  for (const Sampler sampler : {Sampler::kBilinear, Sampler::kNoiseMatched, Sampler::kCubic}) {
    options.sampler = sampler;
    const CostVolume cost = BuildCostVolume(light_field, disparities, options, nullptr);
    for (int y = 0; y < shape.height; ++y)
      for (int x = 0; x < shape.width; ++x)
        for (std::size_t l = 0; l < disparities.size(); ++l) {
          double expected = 0.0;
          for (int v = 0; v < 3; ++v)
            for (int u = 0; u < 3; ++u) {
              if (u == 1 && v == 1) continue;
              const float sx = x - (u - 1) * disparities[l], sy = y - (v - 1) * disparities[l];
              for (int c = 0; c < 3; ++c)
                expected +=
                    std::abs(Sample(light_field, {u, v}, sx, sy, c, sampler) - Centre(light_field, x, y, c, sampler));
            }
          expected *= options.colour_weight / 8.0;
          EXPECT_NEAR(cost.Curve(y, x)[l], expected, 1e-4)
              << SamplerName(sampler) << " at (" << x << ", " << y << "), d = " << disparities[l];
        }
  }
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
