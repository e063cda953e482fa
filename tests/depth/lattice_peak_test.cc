// The lens-lattice measure of depth maps (issue 49): where a lattice can show in a lenslet decode's views, and how
// strongly a 2-D map shows it.

#include "lfsp/depth/lattice_peak.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace lfsp::depth {
namespace {

// The real F01 frames' lattice (lfsp grid on IMG_3 of ../shared/data/lytro_raw/tao_f01).
constexpr double kSpacingX = 9.9311, kSpacingY = 8.6024, kRotation = -0.0049;

bool Contains(const std::vector<MapFrequency>& frequencies, double fx, double fy, double tolerance = 1e-3) {
  for (const MapFrequency& f : frequencies)
    for (const double sign : {1.0, -1.0}) {
      const double dx = sign * f.fx - fx, dy = sign * f.fy - fy;
      if (std::abs(dx - std::round(dx)) < tolerance && std::abs(dy - std::round(dy)) < tolerance) return true;
    }
  return false;
}

TEST(LensLatticeFrequencies, HoldTheJpegBlocksBeatTheBayerTileAndTheHexagonalRows) {
  const std::vector<MapFrequency> f = LensLatticeFrequencies(kSpacingX, 8.6025, 0.0);
  // Lens rows 8.6025 px apart against 8 px JPEG blocks: 0.0753 cycles per row, no alternation (1 block per row).
  EXPECT_TRUE(Contains(f, 0.0, 8.6025 / 8.0 - 1.0));
  // Across: 9.9311 / 8 = 1.2414 cycles per lens -> 0.2414, at sqrt(3)/2 lens per view pixel; one whole cycle per lens
  // puts half a cycle between the two row parities.
  EXPECT_TRUE(Contains(f, 0.2414 * std::sqrt(3.0) / 2.0, 0.5));
  // The Bayer tile (period 2 px, the 4th harmonic of 8) down: 8.6025 / 2 = 4.30 cycles per row.
  EXPECT_TRUE(Contains(f, 0.0, 8.6025 / 2.0 - 4.0));
  // The decoder's own: alternating rows, and the interpolation phase along a row.
  EXPECT_TRUE(Contains(f, 0.0, 0.5));
  EXPECT_TRUE(Contains(f, 1.0 - std::sqrt(3.0) / 2.0, 0.5));
  for (const MapFrequency& frequency : f) {
    EXPECT_GE(frequency.fx, -0.5);
    EXPECT_LE(frequency.fx, 0.5);
    EXPECT_GE(frequency.fy, -0.5);
    EXPECT_LE(frequency.fy, 0.5);
  }
}

TEST(LensLatticeFrequencies, OnlyForSensorDecodes) {
  LightField light_field(LightFieldShape{3, 3, 8, 8, 3});
  EXPECT_FALSE(LensLatticeFrequencies(light_field).has_value());
  light_field.metadata["decode"] = {
      {"grid_spacing_x", kSpacingX}, {"grid_spacing_y", kSpacingY}, {"grid_rotation", kRotation}};
  const auto from_metadata = LensLatticeFrequencies(light_field);
  ASSERT_TRUE(from_metadata.has_value());
  EXPECT_EQ(from_metadata->size(), LensLatticeFrequencies(kSpacingX, kSpacingY, kRotation).size());
}

// Noise of the map's size, smoothed a little as a depth map is.
cv::Mat SmoothNoise(int size, int seed) {
  cv::Mat noise(size, size, CV_32F);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(), 0.8);
  return noise;
}

TEST(StrongestLatticePeak, NoiseReadsAboutOneAndAPlantedLatticeStandsOut) {
  const std::vector<MapFrequency> f = LensLatticeFrequencies(kSpacingX, kSpacingY, kRotation);
  for (int seed = 1; seed <= 3; ++seed) {
    const cv::Mat noise = SmoothNoise(378, seed);
    const LatticePeak clean = StrongestLatticePeak(noise, f).value();
    EXPECT_GT(clean.ratio, 0.5);
    EXPECT_LT(clean.ratio, 2.0);
    // The JPEG blocks' beat down the rows, at a tenth of the noise's amplitude.
    const double fy = kSpacingY / 8.0 - 1.0;
    cv::Mat banded = noise.clone();
    for (int y = 0; y < banded.rows; ++y)
      for (int x = 0; x < banded.cols; ++x)
        banded.at<float>(y, x) += static_cast<float>(0.1 * std::cos(2.0 * std::numbers::pi * fy * y));
    const LatticePeak peak = StrongestLatticePeak(banded, f).value();
    EXPECT_GT(peak.ratio, 4.0);
    EXPECT_NEAR(peak.frequency.fx, 0.0, 0.02);
    EXPECT_NEAR(peak.frequency.fy, fy, 0.02);
  }
}

TEST(StrongestLatticePeak, StreaksThroughZeroFrequencyAreNotALattice) {
  // Lines a pixel wide at 0, 45, 90 and 135 degrees, as semi-global aggregation leaves them in a noisy confidence map:
  // their spectrum is lines through zero frequency, which pass through lattice frequencies such as (0, 1/2).
  cv::Mat map = SmoothNoise(378, 7);
  cv::RNG rng(11);
  for (int k = 0; k < 400; ++k) {
    const int x = rng.uniform(0, map.cols), y = rng.uniform(0, map.rows), length = rng.uniform(8, 30);
    const int direction = rng.uniform(0, 4);
    const int dx[4] = {1, 0, 1, 1}, dy[4] = {0, 1, 1, -1};
    for (int t = 0; t < length; ++t) {
      const int px = x + t * dx[direction], py = y + t * dy[direction];
      if (px >= 0 && px < map.cols && py >= 0 && py < map.rows) map.at<float>(py, px) += 2.0f;
    }
  }
  EXPECT_LT(StrongestLatticePeak(map, LensLatticeFrequencies(kSpacingX, kSpacingY, kRotation)).value().ratio, 2.0);
}

TEST(StrongestLatticePeak, SmallMapsAndNonFiniteValues) {
  const std::vector<MapFrequency> f = LensLatticeFrequencies(kSpacingX, kSpacingY, kRotation);
  EXPECT_FALSE(StrongestLatticePeak(cv::Mat::zeros(100, 300, CV_32F), f).has_value());  // fewer than 2 blocks down
  cv::Mat map = SmoothNoise(200, 5);
  map.at<float>(10, 10) = std::numeric_limits<float>::quiet_NaN();
  map.at<float>(20, 20) = std::numeric_limits<float>::infinity();
  const double ratio = StrongestLatticePeak(map, f).value().ratio;
  EXPECT_TRUE(std::isfinite(ratio));
  EXPECT_GT(ratio, 0.0);
}

}  // namespace
}  // namespace lfsp::depth
