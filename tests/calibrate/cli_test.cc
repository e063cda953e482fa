// `lfsp calibrate` and `lfsp rectify` end to end on small simulated captures, and their clear failures: wrong grid
// size, mixed zoom steps (naming the captures), too few captures, a calibration of another geometry, bad JSON.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "checkerboard_fixture.h"
#include "lfsp/calibrate/calibration_io.h"
#include "lfsp/calibrate/rectify.h"
#include "lfsp/core/load.h"
#include "test_support.h"

namespace lfsp::calibrate {
namespace {

using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

// Four small F01-geometry captures of a 12x9 board as .h5 bundles; the last one at another zoom step.
class CalibrateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    const auto camera = simulate::F01CheckerboardCamera(9, 0.5);
    const auto poses = simulate::CalibrationPoses(camera, 4, 9, 12, 9);
    for (int n = 0; n < 4; ++n) {
      simulate::CheckerboardCaptureOptions options;
      options.camera = camera;
      options.corners_x = 12;
      options.corners_y = 9;
      options.pose = poses[static_cast<std::size_t>(n)];
      options.seed = 40 + static_cast<std::uint32_t>(n);
      if (n == 3) options.zoom_step = 900;
      Bundle bundle;
      bundle.light_field = simulate::RenderCheckerboardLightField(options).light_field;
      SaveLightField(bundle, Path(n));
      // The same capture as a folder of 16-bit PNG views, which carries no weights: dark views are then judged by
      // their brightness.
      if (n == 2) SaveLightField(bundle, (*dir_ / "board2_views").string(), 16);
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Path(int n) { return (*dir_ / ("board" + std::to_string(n) + ".h5")).string(); }
  static TempDir* dir_;
};
TempDir* CalibrateCli::dir_ = nullptr;

TEST_F(CalibrateCli, CalibratesAndRectifies) {
  const std::string cal = (*dir_ / "cal.json").string();
  const auto r = RunLfsp({"calibrate", Path(0), Path(1), Path(2), "--corners", "12x9", "--out", cal});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  std::ifstream file(cal);
  const nlohmann::json j = nlohmann::json::parse(file);
  EXPECT_EQ(j["format"], "lfsp-calibration");
  EXPECT_EQ(j["captures"].size(), 3u);
  EXPECT_LT(j["rms_mm"].get<double>(), 0.1);
  EXPECT_GT(j["captures"][0]["views_used"].size(), 40u);
  EXPECT_EQ(j["H"].size(), 5u);
  // Three captures are below the recommended ten: the file says so.
  EXPECT_FALSE(j["warnings"].empty());
  EXPECT_TRUE(std::filesystem::exists(*dir_ / "cal.summary.json"));

  const std::string out = (*dir_ / "rectified.h5").string();
  const auto rr = RunLfsp({"rectify", Path(0), "--calibration", cal, "--out", out});
  ASSERT_EQ(rr.exit_status, 0) << rr.err;
  const Bundle rectified = LoadLightField(out);
  const Calibration calibration = ReadCalibration(cal);
  const RayModel ideal = RectifiedModel(calibration.model, rectified.light_field.shape());
  const auto& h = rectified.light_field.metadata["calibration"]["H"];
  for (int r2 = 0; r2 < 5; ++r2)
    for (int c = 0; c < 5; ++c)
      EXPECT_DOUBLE_EQ(h[static_cast<std::size_t>(r2)][static_cast<std::size_t>(c)].get<double>(), ideal.H(r2, c));
  EXPECT_TRUE(rectified.light_field.metadata["calibration"]["rectified"].get<bool>());

  // Rectifying twice is refused.
  const auto again = RunLfsp({"rectify", out, "--calibration", cal, "--out", (*dir_ / "twice.h5").string()});
  EXPECT_EQ(again.exit_status, 2);
  EXPECT_NE(again.err.find("already rectified"), std::string::npos) << again.err;
}

// --corners auto: the visible part of the board, whatever its size (for boards that overflow the views, as on the
// real F01 checkerboard). On these fully visible boards it calibrates as well as the exact size does.
TEST_F(CalibrateCli, AutoCornersCalibrateLikeTheExactGridSize) {
  const std::string cal = (*dir_ / "cal_auto.json").string();
  const auto r = RunLfsp({"calibrate", Path(0), Path(1), Path(2), "--corners", "auto", "--out", cal});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  std::ifstream file(cal);
  const nlohmann::json j = nlohmann::json::parse(file);
  std::printf("  --corners auto: rms %.4f mm, board %s in the first capture\n", j["rms_mm"].get<double>(),
              j["checkerboard"]["corners"].dump().c_str());
  EXPECT_LT(j["rms_mm"].get<double>(), 0.1);
  EXPECT_EQ(j["captures"].size(), 3u);
}

TEST_F(CalibrateCli, ViewsFolderWithoutWeightsSkipsTheSameDarkViews) {
  const std::string cal = (*dir_ / "folder.json").string();
  const std::string folder = (*dir_ / "board2_views").string();
  const auto r = RunLfsp({"calibrate", Path(0), Path(1), Path(2), folder, "--corners", "12x9", "--out", cal});
  ASSERT_EQ(r.exit_status, 0) << r.err;
  std::ifstream file(cal);
  const nlohmann::json j = nlohmann::json::parse(file);
  ASSERT_EQ(j["captures"].size(), 4u);
  const auto& from_h5 = j["captures"][2];
  const auto& from_folder = j["captures"][3];
  EXPECT_EQ(from_folder["name"], folder);
  EXPECT_GT(from_folder["dark_views"].size(), 0u);
  EXPECT_NEAR(static_cast<double>(from_folder["views_used"].size()), static_cast<double>(from_h5["views_used"].size()),
              6.0);
  EXPECT_LT(from_folder["rms_mm"].get<double>(), 0.1);
}

TEST_F(CalibrateCli, WrongGridSizeNamesTheProblem) {
  const auto r = RunLfsp({"calibrate", Path(0), Path(1), Path(2), "--out", (*dir_ / "wrong.json").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("19x19"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--corners"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(*dir_ / "wrong.json"));
}

TEST_F(CalibrateCli, MixedZoomStepsNameTheCaptures) {
  const auto r =
      RunLfsp({"calibrate", Path(0), Path(1), Path(3), "--corners", "12x9", "--out", (*dir_ / "mixed.json").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("zoom step 900"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("board3.h5"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("board0.h5"), std::string::npos) << r.err;
  // Allowed on request, with the warning kept in the file.
  const std::string allowed = (*dir_ / "allowed.json").string();
  const auto ok = RunLfsp(
      {"calibrate", Path(0), Path(1), Path(3), "--corners", "12x9", "--allow-mixed-settings", "--out", allowed});
  ASSERT_EQ(ok.exit_status, 0) << ok.err;
  std::ifstream file(allowed);
  const nlohmann::json j = nlohmann::json::parse(file);
  EXPECT_NE(j["warnings"].dump().find("zoom"), std::string::npos);
}

TEST_F(CalibrateCli, TooFewCapturesIsAnError) {
  const auto r = RunLfsp({"calibrate", Path(0), Path(1), "--corners", "12x9", "--out", (*dir_ / "few.json").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("need at least 3"), std::string::npos) << r.err;
}

TEST_F(CalibrateCli, BadCalibrationFilesAreRejected) {
  const std::string bad = (*dir_ / "bad.json").string();
  lfsp::testing::WriteBytes(bad, "{\"format\": \"lfsp-calibration\", \"H\": [1, 2]}");
  const auto r = RunLfsp({"rectify", Path(0), "--calibration", bad, "--out", (*dir_ / "r.h5").string()});
  EXPECT_EQ(r.exit_status, 2);
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;

  // A calibration of another geometry.
  Calibration other;
  other.shape = {11, 11, 380, 380, 1};
  other.model.H = IntrinsicsFromSlopes({0, 3e-4, 1.8e-3, -1.5e-3, 0, 3e-4, 1.8e-3, -1.5e-3}, other.shape);
  const std::string other_path = (*dir_ / "other.json").string();
  WriteCalibration(other, other_path);
  const auto m = RunLfsp({"rectify", Path(0), "--calibration", other_path, "--out", (*dir_ / "m.h5").string()});
  EXPECT_EQ(m.exit_status, 2);
  EXPECT_NE(m.err.find("does not match the calibration"), std::string::npos) << m.err;
}

}  // namespace
}  // namespace lfsp::calibrate
