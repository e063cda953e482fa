// Scene descriptions: built-ins parse, JSON round-trips, and bad input names the field.
#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>

#include "lfsp/core/error.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"
#include "test_support.h"

namespace lfsp::simulate {
namespace {

TEST(Scene, BuiltinsHaveTheRequiredContent) {
  for (const auto& name : BuiltinSceneNames()) {
    const Scene scene = BuiltinScene(name);
    EXPECT_EQ(scene.name, name);
    EXPECT_GE(scene.objects.size(), 2u) << name;
  }
  // "occluders" has bars thinner than 2 px at 128 px; "two-horses" has two similar colours at different depths.
  const Scene occluders = BuiltinScene("occluders");
  int thin = 0;
  for (const auto& o : occluders.objects)
    if (o.name.rfind("bar", 0) == 0) ++thin;
  EXPECT_GE(thin, 3);
  const Scene horses = BuiltinScene("two-horses");
  ASSERT_EQ(horses.objects.size(), 3u);
  const auto& a = horses.objects[1];
  const auto& b = horses.objects[2];
  EXPECT_GT(std::abs(a.disparity - b.disparity), 0.5f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.texture.colour_a[c], b.texture.colour_a[c], 0.03f);
  const auto range = BuiltinScene("planes").DisparityRange();
  EXPECT_LT(range[0], -1.0f);
  EXPECT_GT(range[1], 0.9f);
}

TEST(Scene, JsonRoundTripRendersIdentically) {
  for (const auto& name : BuiltinSceneNames()) {
    const Scene scene = BuiltinScene(name);
    const Scene again = SceneFromJson(nlohmann::json::parse(SceneToJson(scene).dump()));
    RenderOptions options;
    options.nu = options.nv = 3;
    options.width = options.height = 32;
    const auto a = RenderLightField(scene, options);
    const auto b = RenderLightField(again, options);
    EXPECT_EQ(0, std::memcmp(a.light_field.data(), b.light_field.data(), a.light_field.size() * sizeof(float))) << name;
  }
}

TEST(Scene, LoadsFromFileAndRejectsBadInput) {
  testing::TempDir dir;
  testing::WriteBytes(dir / "s.json", SceneToJson(BuiltinScene("spheres")).dump());
  EXPECT_EQ(SceneFromSpec((dir / "s.json").string()).objects.size(), BuiltinScene("spheres").objects.size());
  testing::WriteBytes(dir / "broken.json", "{\"objects\": [");
  try {
    LoadScene(dir / "broken.json");
    FAIL() << "expected lfsp::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos);
  }
  const auto bad = nlohmann::json::parse(
      R"({"objects": [{"disparity": 0, "texture": {"type": "checker", "colours": [[2, 0, 0], [0, 0, 0]]}}]})");
  try {
    SceneFromJson(bad);
    FAIL() << "expected lfsp::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("objects[0].texture.colours[0]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SceneFromJson(nlohmann::json::parse(R"({"objects": []})")), Error);
  EXPECT_THROW(SceneFromJson(nlohmann::json::parse(R"({"objects": [{"texture": {"type": "plaid"}}]})")), Error);
  EXPECT_THROW(SceneFromJson(nlohmann::json::parse(
                   R"({"objects": [{"type": "ellipsoid", "radius": -1, "texture": {"type": "constant"}}]})")),
               Error);
  EXPECT_THROW(SceneFromSpec("no-such-scene"), Error);
}

// A PNG image texture is mapped onto [0,1]^2 of the shorter image side: a 4x4 colour grid shows up in the render.
TEST(Scene, PngImageTexture) {
  testing::TempDir dir;
  cv::Mat bgr(4, 4, CV_8UC3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x)
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>(60 * y), 0, static_cast<uchar>(60 * x));
  ASSERT_TRUE(cv::imwrite((dir / "grid.png").string(), bgr));
  const auto json =
      nlohmann::json::parse(R"({"objects": [{"disparity": 0.5, "texture": {"type": "image", "path": "grid.png"}}]})");
  const Scene scene = SceneFromJson(json, dir.path().string());
  RenderOptions options;
  options.nu = options.nv = 3;
  options.width = options.height = 64;
  const auto r = RenderLightField(scene, options);
  // Centre of image cell (x=2, y=1): red = 120/255, blue = 60/255 (BGR on disk, RGB in memory).
  const int px = 40, py = 24;
  EXPECT_NEAR(r.light_field.at({1, 1}, py, px, 0), 120.0f / 255.0f, 0.02f);
  EXPECT_NEAR(r.light_field.at({1, 1}, py, px, 2), 60.0f / 255.0f, 0.02f);
  EXPECT_THROW(
      SceneFromJson(nlohmann::json::parse(R"({"objects": [{"texture": {"type": "image", "path": "missing.png"}}]})"),
                    dir.path().string()),
      Error);
}

}  // namespace
}  // namespace lfsp::simulate
