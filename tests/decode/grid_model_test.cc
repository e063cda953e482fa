// Lenslet grid model on synthetic white images with exactly known micro-lens centres (Illum, F01 and a small
// Illum-optics sensor, with shot and read noise). Targets (issue 4): centres within 0.05 px RMS of the truth,
// rotation within 1e-4 rad, spacing within 0.01 %.

#include <gtest/gtest.h>

#include <cmath>

#include "lfsp/core/error.h"
#include "lfsp/decode/lenslet_grid.h"
#include "synthetic_lenslet.h"

namespace lfsp::decode {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

struct GridErrors {
  double model_centre_rms = 0.0;     // fitted lattice vs true centres over the usable grid
  double measured_centre_rms = 0.0;  // individual centroids vs true centres (inliers)
  double rotation = 0.0;
  double spacing_x_relative = 0.0;
  double spacing_y_relative = 0.0;
};

GridErrors Compare(const GridEstimate& estimate, const testing::SyntheticCamera& camera) {
  const LensletGrid& grid = estimate.grid;
  GridErrors errors;
  double sum = 0.0;
  long count = 0;
  for (int j = 0; j < grid.rows; ++j)
    for (int i = 0; i < grid.columns; ++i) {
      double x = 0.0, y = 0.0, tx = 0.0, ty = 0.0;
      grid.Centre(i, j, x, y);
      camera.NearestCentre(x, y, tx, ty);
      sum += (x - tx) * (x - tx) + (y - ty) * (y - ty);
      ++count;
    }
  errors.model_centre_rms = std::sqrt(sum / count);
  sum = 0.0;
  count = 0;
  for (const MeasuredCentre& centre : estimate.centres) {
    if (!centre.inlier) continue;
    double tx = 0.0, ty = 0.0;
    camera.NearestCentre(centre.x, centre.y, tx, ty);
    sum += (centre.x - tx) * (centre.x - tx) + (centre.y - ty) * (centre.y - ty);
    ++count;
  }
  errors.measured_centre_rms = std::sqrt(sum / count);
  errors.rotation = std::abs(grid.rotation - camera.rotation);
  errors.spacing_x_relative = std::abs(grid.spacing_x / camera.spacing - 1.0);
  errors.spacing_y_relative = std::abs(grid.spacing_y / (camera.spacing * kHalfSqrt3 * camera.scale_y) - 1.0);
  return errors;
}

// The metadata is only a guess: the real micro-image spacing differs from lensPitch/pixelPitch with the exit pupil
// (up to ~0.1 %), and the rotation is rounded.
GridGuess PerturbedGuess(const testing::SyntheticCamera& camera) {
  GridGuess guess = camera.Guess();
  guess.spacing *= 1.0 - 8e-4;
  guess.scale_y *= 1.0 + 3e-4;
  guess.rotation += 4e-4;
  guess.axis_x += 3.0;
  guess.axis_y -= 2.0;
  return guess;
}

void ExpectOnTarget(const testing::SyntheticCamera& camera, std::uint64_t seed) {
  const RawImage raw = testing::RenderWhiteRaw(camera, 0.8, seed);
  const cv::Mat grey = WhiteImageToGrey(raw, camera.format, "synthetic white");
  const GridEstimate estimate = EstimateLensletGrid(grey, PerturbedGuess(camera));
  const GridErrors errors = Compare(estimate, camera);
  const LensletGrid& grid = estimate.grid;
  ::testing::Test::RecordProperty("model_centre_rms_px", std::to_string(errors.model_centre_rms));
  std::printf(
      "  %dx%d: %d x %d lenses, %d/%d inliers, fit rms %.4f px; centres rms model %.5f px, measured %.4f px; "
      "rotation error %.2e rad; spacing error x %.2e, y %.2e\n",
      camera.width, camera.height, grid.columns, grid.rows, grid.lenses_used, grid.lenses_measured, grid.rms_residual,
      errors.model_centre_rms, errors.measured_centre_rms, errors.rotation, errors.spacing_x_relative,
      errors.spacing_y_relative);
  EXPECT_LT(errors.model_centre_rms, 0.05);
  EXPECT_LT(errors.measured_centre_rms, 0.05);
  EXPECT_LT(errors.rotation, 1e-4);
  EXPECT_LT(errors.spacing_x_relative, 1e-4);
  EXPECT_LT(errors.spacing_y_relative, 1e-4);
  // The residual reports the centroid noise honestly: close to the measured error, never zero.
  EXPECT_GT(grid.rms_residual, 0.0);
  EXPECT_LT(grid.rms_residual, 0.05);
  EXPECT_GT(grid.lenses_used, 0.9 * grid.columns * grid.rows);
}

TEST(GridModel, MiniIllumGeometryWithNoise) { ExpectOnTarget(testing::MiniCamera(), 11); }

TEST(GridModel, F01GeometryWithNoise) { ExpectOnTarget(testing::F01LikeCamera(), 12); }

TEST(GridModel, FullIllumGeometryWithNoise) { ExpectOnTarget(testing::IllumLikeCamera(), 13); }

TEST(GridModel, RobustToCatsEyeBorderMicroImages) {
  // Corner micro-images cut by the main lens: their centroids are biased by up to ~1 px; the fit must not follow.
  testing::SyntheticCamera camera = testing::F01LikeCamera();
  camera.cats_eye = 0.8;
  const RawImage raw = testing::RenderWhiteRaw(camera, 0.8, 21);
  const GridEstimate estimate =
      EstimateLensletGrid(WhiteImageToGrey(raw, camera.format, "synthetic white"), PerturbedGuess(camera));
  const GridErrors errors = Compare(estimate, camera);
  // The border centroids really are off (otherwise this test would test nothing)...
  double worst = 0.0;
  int outliers = 0;
  for (const MeasuredCentre& centre : estimate.centres) {
    double tx = 0.0, ty = 0.0;
    camera.NearestCentre(centre.x, centre.y, tx, ty);
    worst = std::max(worst, std::hypot(centre.x - tx, centre.y - ty));
    if (!centre.inlier) ++outliers;
  }
  std::printf(
      "  cat's eye: worst centroid %.3f px off, %d outliers of %zu; model centres rms %.5f px, rotation "
      "error %.2e, spacing error %.2e\n",
      worst, outliers, estimate.centres.size(), errors.model_centre_rms, errors.rotation, errors.spacing_x_relative);
  EXPECT_GT(worst, 0.3);
  EXPECT_GT(outliers, 100);
  // ... but the lattice is not.
  EXPECT_LT(errors.model_centre_rms, 0.05);
  EXPECT_LT(errors.rotation, 1e-4);
  EXPECT_LT(errors.spacing_x_relative, 1e-4);
  EXPECT_LT(errors.spacing_y_relative, 1e-4);
}

TEST(GridModel, UsableGridAndIndexingFollowTheAxisLens) {
  const testing::SyntheticCamera camera = testing::MiniCamera();
  const RawImage raw = testing::RenderWhiteRaw(camera, 0.8, 3);
  const GridEstimate estimate =
      EstimateLensletGrid(WhiteImageToGrey(raw, camera.format, "synthetic white"), PerturbedGuess(camera));
  const LensletGrid& grid = estimate.grid;
  // Every usable micro-image lies wholly on the sensor, and one more column or row would not.
  double x = 0.0, y = 0.0;
  for (const auto& [i, j] :
       {std::pair{0, 0}, {grid.columns - 1, 0}, {0, grid.rows - 1}, {grid.columns - 1, grid.rows - 1}}) {
    grid.Centre(i, j, x, y);
    EXPECT_GE(x, 0.5 * grid.spacing_x);
    EXPECT_GE(y, 0.5 * grid.spacing_x);
    EXPECT_LE(x, camera.width - 1 - 0.5 * grid.spacing_x);
    EXPECT_LE(y, camera.height - 1 - 0.5 * grid.spacing_x);
  }
  // 1024 px / 14.29 px ~ 71 lenses per row, 768 / 12.38 ~ 61 rows, minus the partial ones at the borders.
  EXPECT_NEAR(grid.columns, 70, 2);
  EXPECT_NEAR(grid.rows, 61, 2);
  // The axis lens sits in an unshifted row: the true centre nearest it is a lattice point of the grid.
  double tx = 0.0, ty = 0.0;
  camera.NearestCentre(camera.axis_x, camera.axis_y, tx, ty);
  const double c = std::cos(grid.rotation), s = std::sin(grid.rotation);
  const double a = (c * (tx - grid.origin_x) + s * (ty - grid.origin_y)) / grid.spacing_x;
  const double b = (-s * (tx - grid.origin_x) + c * (ty - grid.origin_y)) / grid.spacing_y;
  const int j = static_cast<int>(std::lround(b));
  EXPECT_NEAR(b, j, 1e-3);
  EXPECT_EQ(grid.Shift(j), 0);
  EXPECT_NEAR(a, std::round(a), 1e-3);
  // JSON round trip.
  const LensletGrid back = LensletGrid::FromJson(grid.ToJson(), "grid.json");
  EXPECT_EQ(back.columns, grid.columns);
  EXPECT_DOUBLE_EQ(back.rotation, grid.rotation);
}

TEST(GridModel, BadInputThrows) {
  const testing::SyntheticCamera camera = testing::MiniCamera();
  // A flat grey frame has no micro-images to lock on to... but it is bright; a black frame has none at all.
  EXPECT_THROW(EstimateLensletGrid(cv::Mat::zeros(768, 1024, CV_32F), camera.Guess()), Error);
  GridGuess bad = camera.Guess();
  bad.spacing = 1.0;
  EXPECT_THROW(EstimateLensletGrid(cv::Mat::ones(768, 1024, CV_32F), bad), Error);
  EXPECT_THROW(EstimateLensletGrid(cv::Mat::ones(40, 40, CV_32F), camera.Guess()), Error);
  RawImage wrong;
  wrong.width = 100;
  wrong.height = 100;
  wrong.pixels.resize(50);
  EXPECT_THROW(WhiteImageToGrey(wrong, camera.format, "wrong.RAW"), Error);
  EXPECT_THROW(LensletGrid::FromJson(nlohmann::json{{"spacing_x", 14.0}}, "grid.json"), Error);
}

}  // namespace
}  // namespace lfsp::decode
