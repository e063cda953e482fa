// The ray model: distortion inverse, recentring, index inversion, and agreement with the simulator's independent
// implementation of the same model (ground-truth corners lie on their rays).

#include "lfsp/calibrate/ray_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "checkerboard_fixture.h"
#include "lfsp/calibrate/calibration.h"

namespace lfsp::calibrate {
namespace {

TEST(RayModel, UndistortInvertsDistort) {
  const Distortion d{0.15, -0.10, 0.05, -1e-3, 2e-3};
  const auto a = d.ToArray();
  double worst = 0;
  for (double u = -0.4; u <= 0.4; u += 0.05)
    for (double v = -0.4; v <= 0.4; v += 0.05) {
      double pu, pv, mu, mv;
      DistortDirection(a.data(), u, v, pu, pv);
      UndistortDirection(d, pu, pv, 20, mu, mv);
      worst = std::max(worst, std::hypot(mu - u, mv - v));
    }
  // 1e-12 rad is 1e-9 pixels: the fixed point converges fully for this (strong) distortion.
  EXPECT_LT(worst, 1e-12);
}

TEST(RayModel, RecentringMapsTheCentreSampleToTheZeroRay) {
  const LightFieldShape shape{15, 15, 625, 434, 1};
  const RayModel model{IntrinsicsFromSlopes({1e-5, 9e-4, 1.2e-3, -3.6e-3, 2e-5, 9e-4, 1.21e-3, -3.6e-3}, shape), {}};
  const Eigen::Vector4d c = CentreIndex(shape);
  const Ray ray = model.MeasuredRay(c(0), c(1), c(2), c(3));
  EXPECT_NEAR(ray.s, 0, 1e-15);
  EXPECT_NEAR(ray.t, 0, 1e-15);
  EXPECT_NEAR(ray.u, 0, 1e-15);
  EXPECT_NEAR(ray.v, 0, 1e-15);
  // One pixel right changes s by H11 and u by H31.
  const Ray right = model.MeasuredRay(c(0) + 1, c(1), c(2), c(3));
  EXPECT_NEAR(right.s, 1e-5, 1e-15);
  EXPECT_NEAR(right.u, 1.2e-3, 1e-15);
}

TEST(RayModel, IndexOfInvertsPhysicalRay) {
  const auto camera = simulate::IllumCheckerboardCamera(1.0);
  const RayModel model = testing::TrueModel(camera);
  for (double i : {0.0, 100.5, 312.0, 624.0})
    for (double k : {0.0, 7.0, 14.0}) {
      const Ray ray = model.PhysicalRay(i, 433.0 - i / 2, k, 14.0 - k);
      const Eigen::Vector4d n = model.IndexOf(ray, 30);
      EXPECT_NEAR(n(0), i, 1e-7);
      EXPECT_NEAR(n(1), 433.0 - i / 2, 1e-7);
      EXPECT_NEAR(n(2), k, 1e-7);
      EXPECT_NEAR(n(3), 14.0 - k, 1e-7);
    }
}

TEST(RayModel, AgreesWithTheSimulatorsImplementation) {
  // The simulator projects board corners into every view through its own code for the same model; the calibration's
  // point-to-ray distance of those corners under the true model and pose must vanish.
  auto camera = simulate::F01CheckerboardCamera(9, 0.5);
  const auto poses = simulate::CalibrationPoses(camera, 3, 5, 12, 9);
  const RayModel model = testing::TrueModel(camera);
  double worst = 0;
  int checked = 0;
  for (const auto& pose : poses)
    for (int v = 0; v < camera.nv; v += 2)
      for (int u = 0; u < camera.nu; u += 2)
        for (int b = 0; b < 9; b += 4)
          for (int a = 0; a < 12; a += 5) {
            PixelPosition p;
            const double x = a * 3.61e-3, y = b * 3.61e-3;
            if (!simulate::ProjectBoardPoint(camera, pose, x, y, u, v, p)) continue;
            worst = std::max(worst, RayDistance(model, pose.rotation, pose.translation, p.x, p.y, u, v, x, y));
            ++checked;
          }
  EXPECT_GT(checked, 500);
  // Pixel positions are stored as float (about 1e-5 px at these sizes): 1e-7 m is far below the 5e-5 m target.
  EXPECT_LT(worst, 1e-7);
}

}  // namespace
}  // namespace lfsp::calibrate
