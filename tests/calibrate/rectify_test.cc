// Rectification of a simulated distorted capture through a calibration made from other captures: checker lines
// become straight in every view and the views are related by pure disparity shifts; the unrectified capture fails
// the straightness check (so it can fail).

#include "lfsp/calibrate/rectify.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "checkerboard_fixture.h"
#include "lfsp/calibrate/calibration.h"

namespace lfsp::calibrate {
namespace {

constexpr int kCornersX = 12;
constexpr int kCornersY = 9;

// RMS distance of points from their total-least-squares line.
double LineResidual(const std::vector<cv::Point2d>& points) {
  Eigen::Vector2d mean(0, 0);
  for (const auto& p : points) mean += Eigen::Vector2d(p.x, p.y);
  mean /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const auto& p : points) {
    const Eigen::Vector2d d = Eigen::Vector2d(p.x, p.y) - mean;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
  return std::sqrt(eigen.eigenvalues()(0) / static_cast<double>(points.size()));
}

// Largest line-fit residual over every corner row and column of every view.
double WorstLineResidual(const CaptureCorners& corners) {
  double worst = 0;
  for (const auto& view : corners.views) {
    for (int b = 0; b < kCornersY; ++b) {
      std::vector<cv::Point2d> row;
      for (int a = 0; a < kCornersX; ++a) row.push_back(view.corners[static_cast<std::size_t>(b * kCornersX + a)]);
      worst = std::max(worst, LineResidual(row));
    }
    for (int a = 0; a < kCornersX; ++a) {
      std::vector<cv::Point2d> column;
      for (int b = 0; b < kCornersY; ++b) column.push_back(view.corners[static_cast<std::size_t>(b * kCornersX + a)]);
      worst = std::max(worst, LineResidual(column));
    }
  }
  return worst;
}

// For every corner, fit (x, y)(u, v) = (x0 - (u - uc) d, y0 - (v - vc) d) with one disparity d over all views (the
// docs/DESIGN.md convention); returns the RMS residual over all corners and views.
double DisparityShiftResidual(const CaptureCorners& corners) {
  const ViewIndex centre = corners.shape.Centre();
  double sum2 = 0;
  std::size_t count = 0;
  const std::size_t n_corners = static_cast<std::size_t>(kCornersX * kCornersY);
  for (std::size_t n = 0; n < n_corners; ++n) {
    Eigen::MatrixXd a(2 * corners.views.size(), 3);
    Eigen::VectorXd b(2 * corners.views.size());
    for (std::size_t v = 0; v < corners.views.size(); ++v) {
      const auto& view = corners.views[v];
      const auto row = static_cast<Eigen::Index>(2 * v);
      a.row(row) << 1, 0, -(view.view.u - centre.u);
      a.row(row + 1) << 0, 1, -(view.view.v - centre.v);
      b(row) = view.corners[n].x;
      b(row + 1) = view.corners[n].y;
    }
    const Eigen::VectorXd fit = a.colPivHouseholderQr().solve(b);
    const Eigen::VectorXd r = a * fit - b;
    sum2 += r.squaredNorm();
    count += static_cast<std::size_t>(r.size()) / 2;
  }
  return std::sqrt(sum2 / static_cast<double>(count));
}

// A board filling most of the view, nearly facing the camera, rendered without noise so the line fits measure
// geometry rather than corner noise.
simulate::CheckerboardCaptureOptions HeldOutCapture(const simulate::CheckerboardCamera& camera) {
  simulate::CheckerboardCaptureOptions options;
  options.camera = camera;
  options.corners_x = kCornersX;
  options.corners_y = kCornersY;
  options.read_noise = 0;
  options.photons_at_white = 1e12;
  const double square = options.square_size;
  const double span = 0.85 * std::min(camera.width * camera.h[10], camera.height * camera.h[16]);
  const double distance = (kCornersX + 3) * square / span;
  options.pose.rotation = {0.10, -0.08, 0.03};
  const Eigen::Vector3d axis(0.10, -0.08, 0.03);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(axis.norm(), axis.normalized()).toRotationMatrix();
  const Eigen::Vector3d centre = r * Eigen::Vector3d((kCornersX - 1) * square / 2, (kCornersY - 1) * square / 2, 0);
  options.pose.translation = {-centre(0), -centre(1), distance - centre(2)};
  return options;
}

TEST(Rectify, StraightLinesAndPureDisparityShiftsAfterCalibration) {
  // Calibrate on six noisy F01-geometry captures, then rectify another, distorted one.
  const auto camera = simulate::F01CheckerboardCamera(9, 0.6);
  const testing::CaptureSet set = testing::RenderCaptures(camera, 6, kCornersX, kCornersY, 31);
  CalibrationOptions options;
  options.recommended_captures = 6;
  const Calibration calibration = Calibrate(testing::DetectAll(set), options);

  const LightField distorted = simulate::RenderCheckerboardLightField(HeldOutCapture(camera)).light_field;
  const RayModel ideal = RectifiedModel(calibration.model, distorted.shape());
  const LightField rectified = Rectify(distorted, calibration.model, ideal);
  CornerDetectionOptions detection;
  detection.corners_x = kCornersX;
  detection.corners_y = kCornersY;
  const CaptureCorners before = DetectCaptureCorners(distorted, "distorted", detection);
  const CaptureCorners after = DetectCaptureCorners(rectified, "rectified", detection);

  const double lines_before = WorstLineResidual(before), lines_after = WorstLineResidual(after);
  const double shifts_after = DisparityShiftResidual(after);
  std::printf(
      "worst line-fit residual (RMS per row/column of corners, every view): %.3f px before, %.3f px after; "
      "disparity-shift residual (RMS) %.3f px after (%.3f before); %zu views after (%zu before)\n",
      lines_before, lines_after, shifts_after, DisparityShiftResidual(before), after.views.size(), before.views.size());
  EXPECT_LE(lines_after, 0.1);
  EXPECT_LE(shifts_after, 0.1);
  EXPECT_GT(lines_before, 0.1);                            // the distorted capture fails the same criterion
  EXPECT_GE(after.views.size() + 4, before.views.size());  // rectification loses (almost) no usable view
  // The ideal model has square pixels and no distortion.
  EXPECT_EQ(ideal.H(2, 0), ideal.H(3, 1));
  EXPECT_TRUE(ideal.distortion.IsZero());
}

TEST(Rectify, IdentityWhenTheModelIsAlreadyIdeal) {
  const auto camera = simulate::F01CheckerboardCamera(9, 0.5);
  const testing::CaptureSet set = testing::RenderCaptures(camera, 1, kCornersX, kCornersY, 3);
  const LightField& lf = set.captures[0].light_field;
  RayModel model = testing::TrueModel(camera);
  model.distortion = {};
  const LightField same = Rectify(lf, model, model);
  double worst = 0;
  for (std::size_t n = 0; n < lf.size(); ++n)
    worst = std::max(worst, static_cast<double>(std::abs(same.data()[n] - lf.data()[n])));
  EXPECT_LT(worst, 1e-5);
}

}  // namespace
}  // namespace lfsp::calibrate
