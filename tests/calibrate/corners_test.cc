// Corner detection against the simulator's ground-truth corner positions: accuracy, dark views skipped, views at the
// lenslet's edge skipped on decoded captures, a canonical order that survives a half turn of the board, and a clear
// error for a wrong grid size.

#include "lfsp/calibrate/corners.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "checkerboard_fixture.h"
#include "lfsp/core/error.h"

namespace lfsp::calibrate {
namespace {

constexpr int kCornersX = 12;
constexpr int kCornersY = 9;

simulate::CheckerboardCaptureOptions Options(const simulate::BoardPose& pose) {
  simulate::CheckerboardCaptureOptions options;
  options.camera = simulate::IllumCheckerboardCamera(0.5);
  options.corners_x = kCornersX;
  options.corners_y = kCornersY;
  options.pose = pose;
  options.channels = 3;  // exercises the grey conversion
  return options;
}

CornerDetectionOptions Detection() {
  CornerDetectionOptions d;
  d.corners_x = kCornersX;
  d.corners_y = kCornersY;
  return d;
}

// The same board position turned half a turn about its centre: corner (a, b) takes the place of the old corner
// (nx-1-a, ny-1-b).
simulate::BoardPose HalfTurn(const simulate::BoardPose& pose, double square) {
  const Eigen::Vector3d axis(pose.rotation[0], pose.rotation[1], pose.rotation[2]);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(axis.norm(), axis.normalized()).toRotationMatrix();
  const Eigen::Matrix3d turned = r * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d offset = r * Eigen::Vector3d((kCornersX - 1) * square, (kCornersY - 1) * square, 0);
  const Eigen::AngleAxisd aa(turned);
  simulate::BoardPose out;
  const Eigen::Vector3d rv = aa.angle() * aa.axis();
  for (int n = 0; n < 3; ++n) {
    out.rotation[static_cast<std::size_t>(n)] = rv(n);
    out.translation[static_cast<std::size_t>(n)] = pose.translation[static_cast<std::size_t>(n)] + offset(n);
  }
  return out;
}

TEST(Corners, MatchGroundTruthInEveryUsableView) {
  const auto camera = simulate::IllumCheckerboardCamera(0.5);
  const auto pose = simulate::CalibrationPoses(camera, 4, 3, kCornersX, kCornersY)[1];
  const auto capture = simulate::RenderCheckerboardLightField(Options(pose));
  const CaptureCorners found = DetectCaptureCorners(capture.light_field, "sim", Detection());
  const std::vector<double> weights = ViewWeights(capture.light_field);

  // Every view is either used, dark, or failed; dark ones are below the threshold; bright ones are all found. A
  // rendered light field has no known lenslet edge, so none is skipped there.
  EXPECT_EQ(found.views.size() + found.dark_views.size() + found.failed_views.size(), 225u);
  EXPECT_TRUE(found.edge_views.empty());
  for (const auto& v : found.dark_views) EXPECT_LT(weights[static_cast<std::size_t>(CameraNumber(v, 15))], 0.2);
  EXPECT_TRUE(found.failed_views.empty());
  EXPECT_GT(found.views.size(), 140u);

  double sum2 = 0, worst = 0;
  std::size_t count = 0;
  for (const auto& view : found.views) {
    const auto& truth = capture.corners[static_cast<std::size_t>(CameraNumber(view.view, 15))];
    ASSERT_EQ(view.corners.size(), truth.size());
    for (std::size_t n = 0; n < truth.size(); ++n) {
      const double e = std::hypot(view.corners[n].x - truth[n].x, view.corners[n].y - truth[n].y);
      sum2 += e * e;
      worst = std::max(worst, e);
      ++count;
    }
  }
  const double rms = std::sqrt(sum2 / static_cast<double>(count));
  std::printf("corner error over %zu corners: RMS %.4f px, max %.4f px\n", count, rms, worst);
  EXPECT_LT(rms, 0.1);  // the order matches the truth too: a wrong order would give errors of whole squares
  EXPECT_LT(worst, 0.5);
}

TEST(Corners, DecodedCapturesSkipTheViewsAtTheLensletsEdge) {
  const auto camera = simulate::IllumCheckerboardCamera(0.5);
  const auto pose = simulate::CalibrationPoses(camera, 4, 3, kCornersX, kCornersY)[1];
  auto capture = simulate::RenderCheckerboardLightField(Options(pose));
  capture.light_field.metadata["decode"] = nlohmann::json::object();  // as if decoded from a lenslet capture
  const CaptureCorners found = DetectCaptureCorners(capture.light_field, "decoded", Detection());
  const std::vector<double> weights = ViewWeights(capture.light_field);
  const auto dark = [&](int u, int v) {
    return u < 0 || v < 0 || u >= 15 || v >= 15 || weights[static_cast<std::size_t>(CameraNumber({u, v}, 15))] < 0.2;
  };
  // Automatic border 1: exactly the bright views with a dark view or the grid's edge one step away are skipped.
  std::size_t expected_edge = 0;
  for (int v = 0; v < 15; ++v)
    for (int u = 0; u < 15; ++u)
      if (!dark(u, v) && (dark(u - 1, v) || dark(u + 1, v) || dark(u, v - 1) || dark(u, v + 1))) ++expected_edge;
  ASSERT_GT(expected_edge, 0u);
  EXPECT_EQ(found.edge_views.size(), expected_edge);
  for (const auto& e : found.edge_views) {
    EXPECT_FALSE(dark(e.u, e.v));
    EXPECT_TRUE(dark(e.u - 1, e.v) || dark(e.u + 1, e.v) || dark(e.u, e.v - 1) || dark(e.u, e.v + 1));
    for (const auto& used : found.views) EXPECT_FALSE(used.view.u == e.u && used.view.v == e.v);
  }
  EXPECT_EQ(found.views.size() + found.dark_views.size() + found.edge_views.size() + found.failed_views.size(), 225u);

  // An explicit border of 0 keeps them.
  CornerDetectionOptions keep = Detection();
  keep.view_border = 0;
  EXPECT_TRUE(DetectCaptureCorners(capture.light_field, "decoded", keep).edge_views.empty());
}

TEST(Corners, OrderIsCanonicalAfterAHalfTurnOfTheBoard) {
  const auto camera = simulate::IllumCheckerboardCamera(0.5);
  const auto pose = simulate::CalibrationPoses(camera, 4, 3, kCornersX, kCornersY)[2];
  const auto turned = simulate::RenderCheckerboardLightField(Options(HalfTurn(pose, 3.61e-3)));
  const CaptureCorners found = DetectCaptureCorners(turned.light_field, "turned", Detection());
  ASSERT_FALSE(found.views.empty());
  // The board looks the same (colours swapped), so the canonical order starts at the top-left again, which is the
  // turned board's last corner, in every view.
  const std::size_t last = static_cast<std::size_t>(kCornersX * kCornersY - 1);
  double worst = 0;
  for (const auto& view : found.views) {
    const auto& truth = turned.corners[static_cast<std::size_t>(CameraNumber(view.view, 15))];
    for (std::size_t n = 0; n <= last; ++n)
      worst = std::max(worst, std::hypot(view.corners[n].x - truth[last - n].x, view.corners[n].y - truth[last - n].y));
  }
  EXPECT_LT(worst, 0.5);
}

TEST(Corners, CanonicalOrderUndoesRotationsAndRejectsMirrors) {
  // A 4x3 grid, axis-aligned: (a, b) at (10 a, 10 b).
  std::vector<cv::Point2d> grid;
  for (int b = 0; b < 3; ++b)
    for (int a = 0; a < 4; ++a) grid.emplace_back(10 * a, 10 * b);
  std::vector<cv::Point2d> reversed(grid.rbegin(), grid.rend());  // what a detector may return after a half turn
  ASSERT_TRUE(CanonicalCornerOrder(reversed, 4, 3));
  for (std::size_t n = 0; n < grid.size(); ++n) EXPECT_EQ(reversed[n], grid[n]);
  // Mirrored (x flipped in the image): any unmirrored order of it is the mirror's own; corner 0 still top-left.
  std::vector<cv::Point2d> mirrored = grid;
  for (auto& p : mirrored) p.x = -p.x;
  ASSERT_TRUE(CanonicalCornerOrder(mirrored, 4, 3));
  EXPECT_EQ(mirrored[0], cv::Point2d(-30, 0));
  EXPECT_GT(mirrored[1].x, mirrored[0].x);
}

TEST(Corners, WrongGridSizeIsAClearError) {
  const auto camera = simulate::IllumCheckerboardCamera(0.5);
  const auto pose = simulate::CalibrationPoses(camera, 1, 3, kCornersX, kCornersY)[0];
  const auto capture = simulate::RenderCheckerboardLightField(Options(pose));
  CornerDetectionOptions wrong = Detection();
  wrong.corners_x = 19;
  wrong.corners_y = 19;
  try {
    DetectCaptureCorners(capture.light_field, "board.h5", wrong);
    FAIL() << "a 12x9 board was accepted as 19x19";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("board.h5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("19x19"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lfsp::calibrate
