// Scene descriptions: built-ins parse, JSON round-trips, and bad input names the field.
#include <gtest/gtest.h>

#include <cstring>

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

}  // namespace
}  // namespace lfsp::simulate
