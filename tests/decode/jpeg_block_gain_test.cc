// FlattenJpegBlockGain (issue 49): a gain tied to where each view's samples fall down the 8 x 8 blocks of a mosaic
// stored as JPEG, different in each view and channel, is what the quantization leaves in the decoded views of the real
// F01 frames (bands every 13-14 rows). The decoder measures it and divides it out. Here a known gain is put on a
// synthetic light field whose views see a textured plane at disparity 0.7, so the measurement is checked against the
// truth, not against the decoder.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "lfsp/core/hex_lattice.h"
#include "lfsp/core/light_field.h"
#include "lfsp/decode/jpeg_block_gain.h"
#include "textured_plane_views.h"

namespace lfsp::decode {
namespace {

constexpr double kViewStep = 0.993;  // an F01's sensor pixels per view (DecodedGeometryFor)

HexLattice RealF01Lattice() {  // as fitted on IMG_3 of ../shared/data/lytro_raw/tao_f01
  HexLattice lattice;
  lattice.spacing_x = 9.9311;
  lattice.spacing_y = 8.6024;
  lattice.rotation = -0.0049;
  lattice.origin_x = 13.61;
  lattice.origin_y = 29.39;
  return lattice;
}

// Where view (u, v)'s sample of decoded pixel (x, y) falls down the JPEG block, 0 .. 8: the nearest lens's centre
// plus the view's offset. The decoder's rule, written out again here.
double BlockRow(const HexLattice& lattice, int u, int v, int x, int y, int centre) {
  const double shift = 0.5 * lattice.Shift(y);
  double sx = 0.0, sy = 0.0;
  lattice.SensorPosition(std::nearbyint(x * std::sqrt(3.0) / 2.0 - shift) + shift, y, (u - centre) * kViewStep,
                         (v - centre) * kViewStep, sx, sy);
  return sy - 8.0 * std::floor(sy / 8.0);
}

// A smooth texture (sum of oblique waves, values 0.2 .. 0.8) with a weak wave across the rows inside the band
// measure's 11-16 rows (period 15.7 rows, 4 %), so that the scene itself has bands. The step relies on the scene's
// texture near the beat being weak: a 20 % wave there, on this 180-row field, pulled the measured gain to half. A
// grating at the beat's own frequency and tilt (13.3 rows, leaning with the lens rows' drift across the blocks) could
// not be told from the gain at all.
float Texture(double x, double y) {
  return static_cast<float>(0.5 + 0.1 * std::sin(0.31 * x + 0.17 * y) + 0.02 * std::sin(0.02 * x + 0.40 * y + 1.0) +
                            0.1 * std::sin(0.05 * x + 0.07 * y + 2.0));
}

constexpr double kAmplitude = 0.03;

LightField Plane(const HexLattice& lattice, bool with_gain) {
  return testing::TexturedPlaneViews(Texture, [&](int u, int v, int x, int y, int c) {
    // Each channel its own gain: the block envelope takes colour as well as brightness.
    const double phase = 2.0 * std::numbers::pi * BlockRow(lattice, u, v, x, y, 2) / 8.0;
    return with_gain ? 1.0 + kAmplitude * std::cos(phase + c) + 0.3 * kAmplitude * std::cos(2 * phase) : 1.0;
  });
}

// All three channels: each has its own gain.
double RatioRms(const LightField& a, const LightField& b) { return testing::RatioRms(a, b, 0, 2); }

TEST(JpegBlockGain, AKnownGainIsMeasuredAndDividedOut) {
  const HexLattice lattice = RealF01Lattice();
  const LightField clean = Plane(lattice, false);
  LightField banded = Plane(lattice, true);
  const double before = RatioRms(banded, clean);
  const JpegBlockGainReport report = FlattenJpegBlockGain(banded, lattice, kViewStep);
  const double after = RatioRms(banded, clean);
  // The gain's rms over uniformly spread phases: amplitude * sqrt((1 + 0.09) / 2).
  const double put_in = kAmplitude * std::sqrt(1.09 / 2.0);
  std::printf("  gain rms measured %.5f (put in %.5f); views against the clean ones: rms %.5f -> %.5f\n", report.rms,
              put_in, before, after);
  EXPECT_EQ(report.views, 25);
  EXPECT_NEAR(report.rms, put_in, 0.15 * put_in);
  EXPECT_LT(after, 0.15 * before);
}

TEST(JpegBlockGain, ViewsWithoutOneAreLeftAsTheyWere) {
  const HexLattice lattice = RealF01Lattice();
  const LightField clean = Plane(lattice, false);
  LightField flattened = clean;
  const JpegBlockGainReport report = FlattenJpegBlockGain(flattened, lattice, kViewStep);
  std::printf("  gain rms measured on a clean light field %.5f; change %.5f\n", report.rms, RatioRms(flattened, clean));
  EXPECT_LT(report.rms, 0.002);
  EXPECT_LT(RatioRms(flattened, clean), 0.002);
}

TEST(JpegBlockGain, DarkViewsAreLeftAlone) {
  const HexLattice lattice = RealF01Lattice();
  LightField light_field = Plane(lattice, true);
  light_field.EnableWeights(0.0f);
  const LightField before = light_field;
  const JpegBlockGainReport report = FlattenJpegBlockGain(light_field, lattice, kViewStep);
  EXPECT_EQ(report.views, 0);
  EXPECT_EQ(RatioRms(light_field, before), 0.0);
}

}  // namespace
}  // namespace lfsp::decode
