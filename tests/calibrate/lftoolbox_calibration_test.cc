// LFToolbox's CalInfo.json read as an lfsp calibration (issue 17): the real F01 calibration in
// ../shared/data/lytro_views/f01_lftoolbox gives every sample the ray LFToolbox gives it, and the sizes, camera and
// distortion it records.

#include "lfsp/calibrate/lftoolbox_calibration.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lfsp/calibrate/calibration_io.h"
#include "lfsp/core/error.h"
#include "test_support.h"

namespace lfsp::calibrate {
namespace {

namespace fs = std::filesystem;

nlohmann::json ReadJson(const fs::path& path) { return nlohmann::json::parse(testing::ReadBytes(path)); }

TEST(LfToolboxCalibration, RealCalInfoGivesLfToolboxsRays) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path path = data / "lytro_views" / "f01_lftoolbox" / "CalInfo.json";
  const nlohmann::json calinfo = ReadJson(path);
  const Calibration calibration = ReadCalibration(path);
  // CalOptions.LFSize [11 11 379 379 4]: 11 x 11 views of 379 x 379.
  EXPECT_EQ(calibration.shape.nu, 11);
  EXPECT_EQ(calibration.shape.nv, 11);
  EXPECT_EQ(calibration.shape.width, 379);
  EXPECT_EQ(calibration.shape.height, 379);
  EXPECT_EQ(calibration.camera_model, "F01");
  EXPECT_EQ(calibration.serial, "A102430881");
  EXPECT_EQ(calibration.zoom_step, 982);
  EXPECT_EQ(calibration.focus_step, 600);
  ASSERT_EQ(calibration.warnings.size(), 1u);
  const auto& d = calinfo["EstCamDistortionV"];
  EXPECT_EQ(calibration.model.distortion.k1, d[0].get<double>());
  EXPECT_EQ(calibration.model.distortion.b2, d[4].get<double>());

  // Every sample's ray is LFToolbox's H applied to its own 1-based index (view column, view row, pixel column,
  // pixel row), written out here from the JSON.
  const auto& h = calinfo["EstCamIntrinsicsH"];
  for (const auto& [i, j, k, l] : {std::array{0, 0, 0, 0}, {378, 0, 10, 3}, {17, 250, 5, 9}, {189, 189, 5, 5}}) {
    const double n[5] = {k + 1.0, l + 1.0, i + 1.0, j + 1.0, 1.0};
    double expected[4] = {};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 5; ++c) expected[r] += h[r][c].get<double>() * n[c];
    const Ray ray = calibration.model.MeasuredRay(i, j, k, l);
    EXPECT_NEAR(ray.s, expected[0], 1e-15);
    EXPECT_NEAR(ray.t, expected[1], 1e-15);
    EXPECT_NEAR(ray.u, expected[2], 1e-15);
    EXPECT_NEAR(ray.v, expected[3], 1e-15);
  }
  // LFToolbox centres its model: the middle sample of the light field looks straight ahead from the middle of the
  // aperture. With the index order or base wrong it would look far off (|u| ~ 0.3).
  const Eigen::Vector4d centre = CentreIndex(calibration.shape);
  const Ray middle = calibration.model.MeasuredRay(centre[0], centre[1], centre[2], centre[3]);
  EXPECT_LT(std::abs(middle.s), 1e-3);
  EXPECT_LT(std::abs(middle.t), 1e-3);
  EXPECT_LT(std::abs(middle.u), 2e-3);
  EXPECT_LT(std::abs(middle.v), 2e-3);
  // One view step moves the ray's origin across the aperture (0.35 mm) and one pixel step turns it (0.0019 rad).
  const Ray next_view = calibration.model.MeasuredRay(centre[0], centre[1], centre[2] + 1, centre[3]);
  const Ray next_pixel = calibration.model.MeasuredRay(centre[0] + 1, centre[1], centre[2], centre[3]);
  EXPECT_NEAR(next_view.s - middle.s, 3.5e-4, 0.2e-4);
  EXPECT_NEAR(next_pixel.u - middle.u, 1.88e-3, 0.05e-3);
}

TEST(LfToolboxCalibration, MalformedCalInfoNamesTheField) {
  testing::TempDir dir;
  nlohmann::json calinfo = {
      {"EstCamIntrinsicsH", {{1, 0, 0, 0, 0}, {0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}, {0, 0, 0, 0, 1}}},
      {"EstCamDistortionV", {0, 0, 0, 0, 0}},
      {"CalOptions", {{"LFSize", {9, 9, 380, 380, 4}}}}};
  testing::WriteBytes(dir / "good.json", calinfo.dump());
  EXPECT_EQ(ReadCalibration(dir / "good.json").shape.width, 380);
  auto message = [&](const nlohmann::json& broken) {
    testing::WriteBytes(dir / "CalInfo.json", broken.dump());
    return testing::ErrorOf([&] { (void)ReadCalibration(dir / "CalInfo.json"); });
  };
  nlohmann::json no_size = calinfo;
  no_size["CalOptions"].erase("LFSize");
  EXPECT_NE(message(no_size).find("CalInfo.json: calibration field 'CalOptions.LFSize'"), std::string::npos);
  nlohmann::json singular = calinfo;
  singular["EstCamIntrinsicsH"][0][0] = 0;
  EXPECT_NE(message(singular).find("'EstCamIntrinsicsH' is singular"), std::string::npos);
  nlohmann::json short_distortion = calinfo;
  short_distortion["EstCamDistortionV"] = {0.1, 0.2};
  EXPECT_NE(message(short_distortion).find("'EstCamDistortionV' must be 5 numbers"), std::string::npos);
  nlohmann::json fractional = calinfo;
  fractional["CalOptions"]["LFSize"][2] = 379.5;
  EXPECT_NE(message(fractional).find("not a positive whole number"), std::string::npos);
}

}  // namespace
}  // namespace lfsp::calibrate
