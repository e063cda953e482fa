// Calibration against the simulator's ground truth, on reduced Illum and F01 geometries (the full-size Illum case
// is the benchmark bench/calibrate_bench.cc).

#include <gtest/gtest.h>

#include <cstdio>

#include "checkerboard_fixture.h"
#include "lfsp/calibrate/calibration.h"
#include "lfsp/core/error.h"

namespace lfsp::calibrate {
namespace {

using testing::CaptureSet;

void ExpectRecovered(const Calibration& result, const std::vector<CaptureCorners>& observed,
                     const simulate::CheckerboardCamera& camera, double rms_limit_mm) {
  const RayModel truth = testing::TrueModel(camera);
  const Slopes est = result.model.GetSlopes(), tru = truth.GetSlopes();
  const char* names[8] = {"H11", "H13", "H31", "H33", "H22", "H24", "H42", "H44"};
  for (int n = 0; n < 8; ++n) {
    std::printf("%s: estimated %.6e, true %.6e (%+.3f %%)\n", names[n], est[n], tru[n],
                tru[n] != 0 ? 100 * (est[n] - tru[n]) / tru[n] : 0.0);
    if (tru[n] == 0) {
      EXPECT_EQ(est[n], 0.0) << names[n] << " is held at zero (gauge)";
    } else {
      EXPECT_NEAR(est[n], tru[n], 0.005 * std::abs(tru[n])) << names[n] << " beyond 0.5 % of the truth";
    }
  }
  // Offsets: both are recentred for the same shape, so they must agree to the same relative accuracy.
  for (int r = 0; r < 4; ++r) EXPECT_NEAR(result.model.H(r, 4), truth.H(r, 4), 0.005 * std::abs(truth.H(r, 4)) + 1e-9);
  const Distortion& d = result.model.distortion;
  std::printf("distortion: k1 %.5f (true %.5f) k2 %.5f (%.5f) k3 %.5f (%.5f) b1 %.2e (%.2e) b2 %.2e (%.2e)\n", d.k1,
              camera.distortion[0], d.k2, camera.distortion[1], d.k3, camera.distortion[2], d.b1, camera.distortion[3],
              d.b2, camera.distortion[4]);
  // The distortion is recovered when the whole model sends every observed sample along the true ray: the largest
  // direction difference, up to a common rotation, must stay below a tenth of a pixel. (k2, k3 and the decentring
  // trade off against each other, so they are compared as the ray field they produce, k1 directly.)
  const double field_px = testing::MaxDirectionDifferencePixels(result.model, truth, observed);
  std::printf("largest ray-direction difference %.4f px; RMS ray reprojection error %.4f mm\n", field_px,
              result.rms_mm);
  EXPECT_LT(field_px, 0.1);
  EXPECT_NEAR(d.k1, camera.distortion[0], 0.1 * std::abs(camera.distortion[0]));
  EXPECT_LE(result.rms_mm, rms_limit_mm);
  for (const auto& s : result.stages)
    std::printf("stage %s: %.4f mm, %d iterations\n", s.name.c_str(), s.rms_mm, s.iterations);
  // Modelling the distortion must pay off (the simulated camera is distorted).
  ASSERT_EQ(result.stages.size(), 4u);
  EXPECT_LT(result.stages[2].rms_mm, 0.8 * result.stages[1].rms_mm);
}

TEST(Calibration, RecoversIllumGeometry) {
  // 15x15 views at half the Illum resolution, a 12x9 board (larger squares in the smaller views), 8 poses.
  const CaptureSet set = testing::RenderCaptures(simulate::IllumCheckerboardCamera(0.5), 8, 12, 9);
  const auto corners = testing::DetectAll(set);
  CalibrationOptions options;
  options.square_size = set.square_size;
  const Calibration result = Calibrate(corners, options);
  ExpectRecovered(result, corners, set.camera, 0.05);
  EXPECT_EQ(result.captures.size(), 8u);
  for (const auto& c : result.captures) {
    EXPECT_LE(c.rms_mm, 0.06) << c.name;
    EXPECT_GT(c.views.size(), 100u) << c.name;  // of 225 views, the dark corners of the view grid are skipped
  }
}

TEST(Calibration, RecoversF01Geometry) {
  const CaptureSet set = testing::RenderCaptures(simulate::F01CheckerboardCamera(11, 0.6), 8, 12, 9, 23);
  const auto corners = testing::DetectAll(set);
  CalibrationOptions options;
  options.square_size = set.square_size;
  const Calibration result = Calibrate(corners, options);
  ExpectRecovered(result, corners, set.camera, 0.05);
}

}  // namespace
}  // namespace lfsp::calibrate
