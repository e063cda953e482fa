// Scene descriptions: built-ins parse, JSON round-trips, and bad input names the field.
#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"
#include "png_bytes.h"
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

// Runs of `label` along row y of one view of the rendered labels: (first column, length) each.
std::vector<std::pair<int, int>> LabelRuns(const Labels& labels, ViewIndex view, int y, int label) {
  std::vector<std::pair<int, int>> runs;
  const int w = labels.shape().width;
  for (int x = 0; x < w; ++x) {
    if (labels.at(view, y, x) != label) continue;
    if (!runs.empty() && runs.back().first + runs.back().second == x)
      ++runs.back().second;
    else
      runs.push_back({x, 1});
  }
  return runs;
}

// 3x3 views at the 512 x 512 the hard scenes are laid out for, one ray per pixel (labels are exact).
RenderedLightField RenderAt512(const Scene& scene) {
  RenderOptions options;
  options.nu = options.nv = 3;
  options.width = options.height = 512;
  options.supersampling = 1;
  return RenderLightField(scene, options);
}

TEST(Scene, CombHasTeethAndGapsOfOneToFourPixelsAt512) {
  const RenderedLightField comb = RenderAt512(BuiltinScene("comb"));
  // Row 150 crosses the teeth (label 2) above the board: 4 groups of 10 teeth, w px wide with w px gaps, w = 1..4.
  const auto centre = LabelRuns(comb.labels, {1, 1}, 150, 2);
  ASSERT_EQ(centre.size(), 40u);
  for (int group = 0; group < 4; ++group)
    for (int tooth = 0; tooth < 10; ++tooth) {
      const auto& run = centre[static_cast<std::size_t>(group * 10 + tooth)];
      EXPECT_EQ(run.second, group + 1) << "group " << group << " tooth " << tooth;
      if (tooth > 0) {
        EXPECT_EQ(run.first - centre[static_cast<std::size_t>(group * 10 + tooth - 1)].first, 2 * (group + 1));
      }
    }
  // The teeth sit at disparity 1: one view step to the right moves them one pixel left (x - du d).
  const auto right = LabelRuns(comb.labels, {2, 1}, 150, 2);
  ASSERT_EQ(right.size(), centre.size());
  for (std::size_t i = 0; i < centre.size(); ++i) EXPECT_EQ(right[i].first, centre[i].first - 1) << i;
  EXPECT_FLOAT_EQ(comb.disparity.at(150, centre[0].first), 1.0f);
  // The 1 px gaps show the background (-0.9) in the centre view.
  EXPECT_FLOAT_EQ(comb.disparity.at(150, centre[0].first + 1), -0.9f);
}

TEST(Scene, LayersHasFourThinLayersInDepthOrder) {
  const RenderedLightField layers = RenderAt512(BuiltinScene("layers"));
  // A row between the rails crosses 2 px pickets (label 2) every 0.06 of the width (about 31 px).
  const auto pickets = LabelRuns(layers.labels, {1, 1}, 200, 2);
  ASSERT_GE(pickets.size(), 12u);
  for (const auto& run : pickets) EXPECT_LE(run.second, 2);
  // A column crosses the three 3 px rails (label 1), at disparity -0.4, behind the pickets (0.5) and the branch.
  int rail_rows = 0;
  for (int y = 0; y < 512; ++y) rail_rows += layers.labels.at({1, 1}, y, 100) == 1;
  EXPECT_GE(rail_rows, 6);
  EXPECT_LE(rail_rows, 9);
  const auto range = BuiltinScene("layers").DisparityRange();
  EXPECT_FLOAT_EQ(range[0], -1.3f);
  EXPECT_FLOAT_EQ(range[1], 1.9f);
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

std::string TextureError(const std::filesystem::path& dir, const std::string& file) {
  return testing::ErrorOf([&] {
    SceneFromJson(nlohmann::json::parse(R"({"objects": [{"texture": {"type": "image", "path": ")" + file + R"("}}]})"),
                  dir.string());
  });
}

// Image textures were read with cv::imread, past the checks every other image gets: a PNG declaring 30000 x 30000
// pixels made simulate allocate 16 GB, and a truncated one had libpng print a line of its own. They now go through
// ReadImage, which refuses both naming the file.
TEST(Scene, ImageTextureGetsTheImageChecks) {
  testing::TempDir dir;
  testing::WriteBytes(dir / "huge.png", testing::PngDeclaring(100000, 100000));
  std::string error = TextureError(dir.path(), "huge.png");
  EXPECT_NE(error.find("objects[0].texture.path"), std::string::npos) << error;
  EXPECT_NE(error.find((dir / "huge.png").string()), std::string::npos) << error;
  EXPECT_NE(error.find("declares"), std::string::npos) << error;

  cv::Mat grid(16, 16, CV_8UC3, cv::Scalar(10, 20, 30));
  ASSERT_TRUE(cv::imwrite((dir / "whole.png").string(), grid));
  const std::string bytes = testing::ReadBytes(dir / "whole.png");
  testing::WriteBytes(dir / "cut.png", bytes.substr(0, bytes.size() / 2));
  error = TextureError(dir.path(), "cut.png");
  EXPECT_NE(error.find((dir / "cut.png").string()), std::string::npos) << error;
  EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  error = TextureError(dir.path(), "missing.png");
  EXPECT_NE(error.find((dir / "missing.png").string()), std::string::npos) << error;
}

// The texture as cv::imread made it before: Exif orientation applied, BGR to RGB, integers scaled to [0, 1].
cv::Mat ReadAsBefore(const std::filesystem::path& path) {
  const cv::Mat bgr = cv::imread(path.string(), cv::IMREAD_COLOR | cv::IMREAD_ANYDEPTH);
  cv::Mat rgb, texture;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  rgb.convertTo(texture, CV_32FC3, bgr.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
  return texture;
}

// `jpeg` with an Exif block (after its JFIF segment) whose Orientation is `orientation`.
std::string WithExifOrientation(const std::string& jpeg, int orientation) {
  const std::string exif = std::string("Exif\0\0II*\0\x08\0\0\0\x01\0\x12\x01\x03\0\x01\0\0\0", 24) +
                           static_cast<char>(orientation) + std::string(7, '\0');
  const std::size_t length = exif.size() + 2;
  const std::string segment =
      std::string("\xFF\xE1") + static_cast<char>(length >> 8) + static_cast<char>(length & 0xFF) + exif;
  const std::size_t after_jfif = 4 + ((static_cast<unsigned char>(jpeg[4]) << 8) | static_cast<unsigned char>(jpeg[5]));
  return jpeg.substr(0, after_jfif) + segment + jpeg.substr(after_jfif);
}

// Grey, RGBA, 16-bit and JPEG textures (one turned by its Exif orientation) read as they did with cv::imread: the
// same size and orientation, and the same samples but for the last bit of some (k / 255.0f, as ReadImage maps every
// 8-bit value, against cv::convertTo's k * (1 / 255.0)).
TEST(Scene, ImageTexturesReadAsBefore) {
  testing::TempDir dir;
  cv::Mat noise(6, 10, CV_8UC3);
  cv::randu(noise, 0, 256);
  std::vector<std::uint8_t> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", noise, jpeg));
  testing::WriteBytes(dir / "photo.jpg", std::string(jpeg.begin(), jpeg.end()));
  for (const int orientation : {3, 6, 8})
    testing::WriteBytes(dir / ("turned" + std::to_string(orientation) + ".jpg"),
                        WithExifOrientation(std::string(jpeg.begin(), jpeg.end()), orientation));
  cv::Mat deep(6, 10, CV_16UC3), rgba(6, 10, CV_8UC4), grey(6, 10, CV_8UC1);
  cv::randu(deep, 0, 65536);
  cv::randu(rgba, 0, 256);
  cv::randu(grey, 0, 256);
  ASSERT_TRUE(cv::imwrite((dir / "deep.png").string(), deep));
  ASSERT_TRUE(cv::imwrite((dir / "rgba.png").string(), rgba));
  ASSERT_TRUE(cv::imwrite((dir / "grey.png").string(), grey));
  for (const std::string name :
       {"photo.jpg", "turned3.jpg", "turned6.jpg", "turned8.jpg", "deep.png", "rgba.png", "grey.png"}) {
    const Scene scene = SceneFromJson(
        nlohmann::json::parse(R"({"objects": [{"texture": {"type": "image", "path": ")" + name + R"("}}]})"),
        dir.path().string());
    const cv::Mat& texture = *scene.objects.at(0).texture.image;
    const cv::Mat before = ReadAsBefore(dir / name);
    ASSERT_EQ(texture.type(), CV_32FC3) << name;
    ASSERT_EQ(texture.size(), before.size()) << name;
    EXPECT_LT(cv::norm(texture, before, cv::NORM_INF), 1e-6) << name;
  }
  EXPECT_EQ(ReadAsBefore(dir / "turned6.jpg").size(), cv::Size(6, 10));  // imread did turn it
}

}  // namespace
}  // namespace lfsp::simulate
