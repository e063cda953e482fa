// Corner detection and tracking on a real decoded F01 checkerboard capture (issue 13, item 4):
// ../shared/data/lytro_views/f01_checkerboard, 7x7 views of 328x328 named view_<row>_<col>.png (1-based). The board
// overflows every view, so the partial-board mode is used. Every view must give the same corners, and each corner
// must move linearly with the view index (its disparity line): the residual of those fits is the measure.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>

#include "lfsp/calibrate/corners.h"
#include "lfsp/core/image_io.h"
#include "test_support.h"

namespace lfsp::calibrate {
namespace {

namespace fs = std::filesystem;

// The folder as a light field: view (u, v) = view_<v+1>_<u+1>.png.
LightField ReadRowColumnViews(const fs::path& folder, int views) {
  const ImageFile first = ReadImage(folder / "view_1_1.png");
  LightFieldShape shape;
  shape.nu = shape.nv = views;
  shape.width = first.pixels.cols;
  shape.height = first.pixels.rows;
  shape.channels = 3;
  LightField light_field(shape);
  for (int v = 0; v < views; ++v)
    for (int u = 0; u < views; ++u) {
      cv::Mat view = light_field.View({u, v});
      ReadImageInto(folder / ("view_" + std::to_string(v + 1) + "_" + std::to_string(u + 1) + ".png"), view);
    }
  return light_field;
}

TEST(RealCheckerboard, CornersInEveryViewFollowDisparityLines) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LightField light_field = ReadRowColumnViews(data / "lytro_views" / "f01_checkerboard", 7);
  CornerDetectionOptions options;
  options.corners_x = options.corners_y = 0;  // the board is larger than the views
  options.min_view_weight = 0.0;              // every view, however dim
  const CaptureCorners corners = DetectCaptureCorners(light_field, "f01_checkerboard", options);
  EXPECT_EQ(corners.views.size(), 49u);
  EXPECT_TRUE(corners.failed_views.empty());
  EXPECT_GE(corners.corners_x * corners.corners_y, 64);
  std::printf("  board: %d x %d corners tracked in %zu views (reference u=%d v=%d)\n", corners.corners_x,
              corners.corners_y, corners.views.size(), corners.reference.u, corners.reference.v);

  // Per corner: x and y affine in (u, v); residual over all views and corners.
  const std::size_t count = static_cast<std::size_t>(corners.corners_x * corners.corners_y);
  double sum_squares = 0.0, worst = 0.0, disparity_sum = 0.0;
  long samples = 0;
  for (std::size_t n = 0; n < count; ++n) {
    Eigen::MatrixXd design(static_cast<Eigen::Index>(corners.views.size()), 3);
    Eigen::VectorXd xs(design.rows()), ys(design.rows());
    for (std::size_t k = 0; k < corners.views.size(); ++k) {
      const ViewCorners& view = corners.views[k];
      design.row(static_cast<Eigen::Index>(k)) << 1.0, view.view.u - 3.0, view.view.v - 3.0;
      xs(static_cast<Eigen::Index>(k)) = view.corners[n].x;
      ys(static_cast<Eigen::Index>(k)) = view.corners[n].y;
    }
    const Eigen::Vector3d fx = design.colPivHouseholderQr().solve(xs);
    const Eigen::Vector3d fy = design.colPivHouseholderQr().solve(ys);
    const Eigen::VectorXd rx = design * fx - xs, ry = design * fy - ys;
    for (Eigen::Index k = 0; k < rx.size(); ++k) {
      const double r = std::hypot(rx(k), ry(k));
      sum_squares += r * r;
      worst = std::max(worst, r);
      ++samples;
    }
    disparity_sum += std::hypot(fx(1), fy(2));
  }
  const double rms = std::sqrt(sum_squares / static_cast<double>(samples));
  std::printf("  disparity-line fit: rms %.3f px, worst %.3f px, mean |disparity| %.3f px/view\n", rms, worst,
              disparity_sum / static_cast<double>(count));
  RecordProperty("line_fit_rms_px", std::to_string(rms));
  EXPECT_LT(rms, 0.3);
}

}  // namespace
}  // namespace lfsp::calibrate
