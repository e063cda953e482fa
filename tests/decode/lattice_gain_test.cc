// FlattenLatticeGain (issue 13): a gain tied to where each decoded pixel's lens centre falls on the sensor's 2 x 2
// Bayer tile, the same in every view, is what a wrong devignetting leaves in a lenslet decode (a white image
// estimated from the capture, one taken at another zoom). The decoder measures it and divides it out. Here a known
// gain is put on a synthetic light field whose views see a textured plane at disparity 0.7, so the measurement is
// checked against the truth, not against the decoder.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "lfsp/core/hex_lattice.h"
#include "lfsp/core/light_field.h"
#include "lfsp/decode/lattice_gain.h"
#include "textured_plane_views.h"

namespace lfsp::decode {
namespace {

HexLattice F01LikeLattice() {
  HexLattice lattice;
  lattice.spacing_x = 9.9276;
  lattice.spacing_y = 8.6018;
  lattice.rotation = 0.0019;
  lattice.origin_x = 16.46;
  lattice.origin_y = 10.22;
  lattice.row_shift = 1;
  return lattice;
}

// The sensor position of the lens nearest to where decoded pixel (x, y) is sampled: x * sqrt(3)/2 pitches along lens
// row y (DecodedGeometry), rounded to a lens. The same rule as the decoder's, written out again here.
void LensPosition(const HexLattice& lattice, int x, int y, double& sx, double& sy) {
  const double shift = 0.5 * lattice.Shift(y);
  lattice.SensorPosition(std::nearbyint(x * std::sqrt(3.0) / 2.0 - shift) + shift, y, 0.0, 0.0, sx, sy);
}

// A smooth texture (sum of oblique waves, values 0.2 .. 0.8).
float Texture(double x, double y) {
  return static_cast<float>(0.5 + 0.1 * std::sin(0.31 * x + 0.17 * y) + 0.1 * std::sin(0.11 * x - 0.23 * y + 1.0) +
                            0.1 * std::sin(0.05 * x + 0.07 * y + 2.0));
}

constexpr double kAmplitude = 0.005;

LightField Plane(const HexLattice& lattice, bool with_gain) {
  return testing::TexturedPlaneViews(Texture, [&](int u, int, int x, int y, int) {
    if (!with_gain) return 1.0;
    double sx = 0.0, sy = 0.0;
    LensPosition(lattice, x, y, sx, sy);
    return 1.0 + kAmplitude * std::cos(std::numbers::pi * sx) * std::cos(std::numbers::pi * sy) * (1.0 + 0.2 * (u - 2));
  });
}

// Green only: the lattice gain is one for all channels.
double RatioRms(const LightField& a, const LightField& b) { return testing::RatioRms(a, b, 1, 1); }

TEST(LatticeGain, AKnownGainIsMeasuredAndDividedOut) {
  const HexLattice lattice = F01LikeLattice();
  const LightField clean = Plane(lattice, false);
  LightField patterned = Plane(lattice, true);
  const double before = RatioRms(patterned, clean);
  const LatticeGainReport report = FlattenLatticeGain(patterned, lattice);
  const double after = RatioRms(patterned, clean);
  // The gain's rms over uniformly spread phases is amplitude / 2 times the view's factor (0.6 .. 1.4, mean 1).
  std::printf("  gain rms measured %.5f (put in about %.5f); views against the clean ones: rms %.5f -> %.5f\n",
              report.rms, kAmplitude / 2, before, after);
  EXPECT_EQ(report.views, 25);
  EXPECT_NEAR(report.rms, kAmplitude / 2, 0.3 * kAmplitude / 2);
  EXPECT_LT(after, 0.3 * before);
}

TEST(LatticeGain, ViewsWithoutOneAreLeftAsTheyWere) {
  const HexLattice lattice = F01LikeLattice();
  const LightField clean = Plane(lattice, false);
  LightField flattened = clean;
  const LatticeGainReport report = FlattenLatticeGain(flattened, lattice);
  std::printf("  gain rms measured on a clean light field %.5f; change %.5f\n", report.rms, RatioRms(flattened, clean));
  EXPECT_LT(report.rms, 0.0005);
  EXPECT_LT(RatioRms(flattened, clean), 0.0005);
}

}  // namespace
}  // namespace lfsp::decode
