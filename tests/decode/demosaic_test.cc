// The gradient demosaic near a micro-image's edge: the missing channels of a pixel whose outer neighbours lie under
// the next micro-lens must stand for that pixel's own position. On a colour ramp with constant colour differences
// the one-sided estimate is exact; copying the inner neighbour instead (as before) is a pixel off, which made the
// F01's outer views (8, 4) read as if sampled a third of a view step towards the centre. On a finer texture the
// one-sided estimate is exact no longer and lags towards the lens centre, so where a pixel has a complete pair of
// neighbours under its lens, that pair alone gives the estimate.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>

#include "lfsp/decode/demosaic.h"

namespace lfsp::decode {
namespace {

constexpr int kSize = 40;
constexpr int kBoundary = 20;  // first row / column under the second micro-lens
constexpr float kSlope = 0.01f;
constexpr float kOffset[3] = {0.2f, 0.3f, 0.25f};  // r, g, b at position 0
constexpr float kNextLens = 5.0f;                  // what the second micro-image holds, far from the ramp

// The ramp's true value of `channel` at the pixel, along x (across a vertical lens boundary) or along y.
float Ramp(int channel, int x, int y, bool along_x) {
  return kOffset[channel] + kSlope * static_cast<float>(along_x ? x : y);
}

// An RGGB Bayer image of the ramp over one micro-lens and a flat, bright neighbouring one, with the labels and a dim
// white image that sends every pixel through the edge interpolation. The ramp's lens lies before the boundary
// (missing neighbours on the +x / +y side) or, `ramp_beyond`, after it (on the -x / -y side).
struct EdgeScene {
  cv::Mat bayer, labels, white;
  EdgeScene(bool along_x, bool ramp_beyond)
      : bayer(kSize, kSize, CV_32F), labels(kSize, kSize, CV_8U), white(kSize, kSize, CV_32F, cv::Scalar(0.1)) {
    constexpr int kTile[4] = {0, 1, 1, 2};  // RGGB
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const bool beyond = (along_x ? x : y) >= kBoundary;
        const int channel = kTile[2 * (y & 1) + (x & 1)];
        labels.at<std::uint8_t>(y, x) = beyond ? 1 : 0;
        bayer.at<float>(y, x) = beyond == ramp_beyond ? Ramp(channel, x, y, along_x) : kNextLens;
      }
  }
  cv::Mat Demosaicked() const {
    const MicroImages micro_images{white, labels};
    return Demosaic(bayer, BayerPattern::kRGGB, DemosaicMethod::kGradient, 8.0f, &micro_images);
  }
};

// The three pixels of the ramp's lens nearest the boundary, along every line across it, in every channel.
void CheckEdgeOfTheRampsLens(bool along_x, bool ramp_beyond) {
  const cv::Mat rgb = EdgeScene(along_x, ramp_beyond).Demosaicked();
  const int first = ramp_beyond ? kBoundary : kBoundary - 3;
  int checked = 0;
  for (int across = 4; across < kSize - 4; ++across)
    for (int along = first; along < first + 3; ++along) {
      const int x = along_x ? along : across, y = along_x ? across : along;
      const cv::Vec3f pixel = rgb.at<cv::Vec3f>(y, x);
      for (int channel = 0; channel < 3; ++channel) {
        EXPECT_NEAR(pixel[channel], Ramp(channel, x, y, along_x), 1e-5)
            << "pixel (" << x << ", " << y << ") channel " << channel;
        ++checked;
      }
    }
  EXPECT_EQ(checked, 3 * 3 * (kSize - 8));
}

TEST(Demosaic, PixelsBesideTheNextMicroLensKeepTheirOwnPositionAcrossColumns) {
  CheckEdgeOfTheRampsLens(true, false);
  CheckEdgeOfTheRampsLens(true, true);
}
TEST(Demosaic, PixelsBesideTheNextMicroLensKeepTheirOwnPositionAcrossRows) {
  CheckEdgeOfTheRampsLens(false, false);
  CheckEdgeOfTheRampsLens(false, true);
}

// Away from the boundary too (the whole image goes through the edge interpolation here), no value of the next
// micro-image (5) reaches a pixel of the ramp's lens (values below 1): every pair there has a neighbour under the
// pixel's own lens.
TEST(Demosaic, TheNextMicroImageStaysOut) {
  const cv::Mat rgb = EdgeScene(true, false).Demosaicked();
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kBoundary; ++x)
      for (int channel = 0; channel < 3; ++channel) ASSERT_LT(rgb.at<cv::Vec3f>(y, x)[channel], 1.0f);
}

// A grey texture along x (a sinusoid of period 6.7 px: what a texture of period 10 view pixels at disparity 1.5 draws
// in a micro-image, one sensor pixel per view step) over the ramp's lens, beside a vertical boundary: the luminance
// of the three columns nearest the boundary must not lag behind the texture towards the lens (which made the outer
// views read |disparity| too small). Their least-squares shift against the truth: -0.175 px when the one-sided
// estimates took K(q) along the pair and were averaged with complete pairs; -0.152 with the complete pairs alone
// where there are any; -0.104 with K(q) across the pair as well. What is left comes from the red of blue pixels and
// the blue of red ones, whose colour has no pixel on q's column.
TEST(Demosaic, AFineTextureBesideTheNextMicroLensDoesNotLagInwards) {
  constexpr double kFrequency = 0.15;  // cycles per pixel
  auto truth = [&](double x) { return 0.5 + 0.2 * std::sin(2.0 * M_PI * kFrequency * x + 0.4); };
  auto slope = [&](double x) { return 0.2 * 2.0 * M_PI * kFrequency * std::cos(2.0 * M_PI * kFrequency * x + 0.4); };
  EdgeScene scene(true, false);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kBoundary; ++x) scene.bayer.at<float>(y, x) = static_cast<float>(truth(x));
  const cv::Mat rgb = scene.Demosaicked();
  double along = 0.0, norm = 0.0;
  for (int y = 4; y < kSize - 4; ++y)
    for (int x = kBoundary - 3; x < kBoundary; ++x) {
      const cv::Vec3f pixel = rgb.at<cv::Vec3f>(y, x);
      const double luminance = (pixel[0] + pixel[1] + pixel[2]) / 3.0;
      along += (luminance - truth(x)) * slope(x);
      norm += slope(x) * slope(x);
    }
  const double shift = along / norm;  // luminance(x) ~ truth(x + shift)
  std::printf("  least-squares shift of the luminance beside the boundary: %+.4f px\n", shift);
  EXPECT_LT(std::abs(shift), 0.12);
}

}  // namespace
}  // namespace lfsp::decode
