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
  // 15x15 views at half the Illum resolution, a 12x9 board (larger squares in the smaller views), 6 poses.
  const CaptureSet set = testing::RenderCaptures(simulate::IllumCheckerboardCamera(0.5), 6, 12, 9);
  const auto corners = testing::DetectAll(set);
  CalibrationOptions options;
  options.square_size = set.square_size;
  const Calibration result = Calibrate(corners, options);
  ExpectRecovered(result, corners, set.camera, 0.05);
  EXPECT_EQ(result.captures.size(), 6u);
  for (const auto& c : result.captures) {
    EXPECT_LE(c.rms_mm, 0.06) << c.name;
    EXPECT_GT(c.views.size(), 100u) << c.name;  // of 225 views, the dark corners of the view grid are skipped
  }
}

TEST(Calibration, RecoversF01Geometry) {
  const CaptureSet set = testing::RenderCaptures(simulate::F01CheckerboardCamera(11, 0.6), 6, 12, 9, 23);
  const auto corners = testing::DetectAll(set);
  CalibrationOptions options;
  options.square_size = set.square_size;
  const Calibration result = Calibrate(corners, options);
  ExpectRecovered(result, corners, set.camera, 0.05);
}

// Corners straight from the simulator's projection (no image, no noise): the solver alone must find the model.
CaptureCorners ExactCorners(const simulate::CheckerboardCamera& camera, const simulate::BoardPose& pose,
                            const std::string& name, int max_views = 1000) {
  CaptureCorners c;
  c.name = name;
  c.shape = {camera.nu, camera.nv, camera.width, camera.height, 1};
  c.corners_x = 12;
  c.corners_y = 9;
  c.reference = c.shape.Centre();
  for (int v = 0; v < camera.nv; ++v)
    for (int u = 0; u < camera.nu; ++u) {
      if (static_cast<int>(c.views.size()) >= max_views) break;
      ViewCorners view{{u, v}, {}};
      for (int b = 0; b < 9; ++b)
        for (int a = 0; a < 12; ++a) {
          PixelPosition p;
          if (!simulate::ProjectBoardPoint(camera, pose, a * 3.61e-3, b * 3.61e-3, u, v, p)) continue;
          view.corners.emplace_back(p.x, p.y);
        }
      if (view.corners.size() == 108u) c.views.push_back(std::move(view));
    }
  if (max_views >= 1000) c.reference = c.views[c.views.size() / 2].view;
  return c;
}

TEST(Calibration, NoiseFreeCornersGiveTheExactModel) {
  const auto camera = simulate::F01CheckerboardCamera(9, 0.5);
  const auto poses = simulate::CalibrationPoses(camera, 5, 17, 12, 9);
  std::vector<CaptureCorners> captures;
  for (std::size_t n = 0; n < poses.size(); ++n)
    captures.push_back(ExactCorners(camera, poses[n], "exact" + std::to_string(n)));
  CalibrationOptions options;
  options.recommended_captures = 5;
  const Calibration result = Calibrate(captures, options);
  const Slopes est = result.model.GetSlopes(), tru = testing::TrueModel(camera).GetSlopes();
  for (int n = 0; n < 8; ++n) EXPECT_NEAR(est[n], tru[n], 1e-5 * std::abs(tru[n])) << "slope " << n;
  const auto d = result.model.distortion.ToArray();
  for (int n = 0; n < 5; ++n) EXPECT_NEAR(d[n], camera.distortion[n], n < 3 ? 2e-3 : 2e-5) << "distortion " << n;
  EXPECT_LT(result.rms_mm, 1e-4);  // float corner positions leave ~1e-5 px
  for (std::size_t n = 0; n < poses.size(); ++n)
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(result.captures[n].rotation[i], poses[n].rotation[i], 1e-5);
      EXPECT_NEAR(result.captures[n].translation[i], poses[n].translation[i], 1e-6);
    }
}

TEST(Calibration, TooFewViewsOrCapturesAreReportedByName) {
  const auto camera = simulate::F01CheckerboardCamera(9, 0.5);
  const auto poses = simulate::CalibrationPoses(camera, 4, 17, 12, 9);
  std::vector<CaptureCorners> captures{ExactCorners(camera, poses[0], "good0.h5"),
                                       ExactCorners(camera, poses[1], "good1.h5"),
                                       ExactCorners(camera, poses[2], "dark2.h5", 3)};
  try {
    Calibrate(captures);
    FAIL() << "two usable captures were accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("need at least 3"), std::string::npos) << m;
    EXPECT_NE(m.find("dark2.h5"), std::string::npos) << m;  // the rejected capture is named, with its view count
    EXPECT_NE(m.find("only 3 views"), std::string::npos) << m;
  }
  // With a fourth good capture it works, and the dropped one is listed.
  captures.push_back(ExactCorners(camera, poses[3], "good3.h5"));
  const Calibration result = Calibrate(captures);
  ASSERT_EQ(result.rejected_captures.size(), 1u);
  EXPECT_NE(result.rejected_captures[0].find("dark2.h5"), std::string::npos);
  EXPECT_EQ(result.captures.size(), 3u);
  EXPECT_FALSE(result.warnings.empty());
}

TEST(Calibration, MismatchedCapturesAreErrorsNamingThem) {
  const auto camera = simulate::F01CheckerboardCamera(9, 0.5);
  const auto poses = simulate::CalibrationPoses(camera, 3, 17, 12, 9);
  std::vector<CaptureCorners> captures;
  for (int n = 0; n < 3; ++n)
    captures.push_back(ExactCorners(camera, poses[static_cast<std::size_t>(n)], "c" + std::to_string(n)));
  auto resized = captures;
  resized[2].shape.width += 2;
  EXPECT_THROW(
      {
        try {
          Calibrate(resized);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("c2"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
  auto refocused = captures;
  refocused[0].focus_step = 100;
  refocused[1].focus_step = 100;
  refocused[2].focus_step = 250;
  try {
    Calibrate(refocused);
    FAIL() << "mixed focus steps were accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("focus step 250: c2"), std::string::npos) << m;
    EXPECT_NE(m.find("focus step 100: c0, c1"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace lfsp::calibrate
