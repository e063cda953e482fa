// Checkerboard captures for calibration: the rendered corners are where the ground truth says, in every view.
#include <gtest/gtest.h>

#include <cmath>

#include "lfsp/simulate/calibration_set.h"
#include "lfsp/simulate/render.h"

namespace lfsp::simulate {
namespace {

float Luma(const LightField& lf, ViewIndex view, float x, float y) {
  const int xi = static_cast<int>(std::lround(x)), yi = static_cast<int>(std::lround(y));
  return lf.at(view, yi, xi, 1);
}

TEST(CalibrationSet, CornersAreWhereTheGroundTruthSaysInEveryView) {
  const auto boards = CalibrationBoards(5);
  ASSERT_EQ(boards.size(), 5u);
  RenderOptions options;
  options.nu = options.nv = 5;
  options.width = 240;
  options.height = 180;
  options.supersampling = 2;
  int checked = 0;
  for (const Board& board : boards) {
    const Scene scene = CalibrationScene(board, CalibrationRig());
    const RenderedLightField r = RenderLightField(scene, options);
    const auto truth = CalibrationGroundTruth(scene, options.width, options.height);
    ASSERT_EQ(truth["corners"].size(), 35u);
    for (const auto& corner : truth["corners"]) {
      const float x = corner["centre_px"][0].get<float>(), y = corner["centre_px"][1].get<float>();
      const float d = corner["disparity"].get<float>();
      ASSERT_GT(x, 4);
      ASSERT_LT(x, options.width - 5);
      ASSERT_GT(y, 4);
      ASSERT_LT(y, options.height - 5);
      // The board plane's disparity is exact at the corner (analytic plane), and the corner is on the board.
      const int xi = static_cast<int>(std::lround(x)), yi = static_cast<int>(std::lround(y));
      EXPECT_NEAR(r.disparity.at(yi, xi), d, 0.02f);
      EXPECT_EQ(r.labels.at({2, 2}, yi, xi), 1);
      for (const ViewIndex view :
           {ViewIndex{0, 0}, ViewIndex{4, 0}, ViewIndex{2, 2}, ViewIndex{0, 4}, ViewIndex{4, 4}}) {
        const float px = x - static_cast<float>(view.u - 2) * d, py = y - static_cast<float>(view.v - 2) * d;
        // Around a corner the diagonal quadrants match and the neighbouring ones differ.
        const float a = Luma(r.light_field, view, px + 2.5f, py + 2.5f);
        const float b = Luma(r.light_field, view, px - 2.5f, py - 2.5f);
        const float c = Luma(r.light_field, view, px + 2.5f, py - 2.5f);
        const float e = Luma(r.light_field, view, px - 2.5f, py + 2.5f);
        EXPECT_NEAR(a, b, 0.2f);
        EXPECT_NEAR(c, e, 0.2f);
        EXPECT_GT(std::abs(a - c), 0.5f);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 5 * 35 * 5);
}

TEST(CalibrationSet, PosesVaryInTiltAndDistance) {
  const auto boards = CalibrationBoards(6);
  float zmin = 10, zmax = 0;
  int tilted = 0;
  for (const Board& b : boards) {
    const auto c = BoardToCamera(b, 0.1f, 0.075f);
    zmin = std::min(zmin, c[2]);
    zmax = std::max(zmax, c[2]);
    if (std::hypot(b.rotation[0], b.rotation[1]) > 0.2f) ++tilted;
  }
  EXPECT_GT(zmax - zmin, 0.1f);
  EXPECT_GE(tilted, 5);
}

}  // namespace
}  // namespace lfsp::simulate
