// `lfsp recolor` and `lfsp refocus` end to end: outputs, summaries, exactness outside the edit, bad input.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/edit/image_measures.h"
#include "synthetic_light_field.h"
#include "test_support.h"

namespace lfsp::edit {
namespace {

using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

constexpr int kViews = 7;
constexpr int kSize = 64;

// A foreground card (label 1, disparity 1.5) over a background (label 0, disparity -1), written as a bundle with
// disparity and, when asked, labels.
struct Scene {
  testing::TwoPlaneScene planes;
  Bundle bundle;
};

Scene MakeScene(bool with_labels) {
  Scene scene;
  scene.planes.x0 = 20.0f;
  scene.planes.y0 = 18.0f;
  scene.planes.x1 = 44.0f;
  scene.planes.y1 = 42.0f;
  Labels labels;
  DisparityMap disparity;
  scene.bundle.light_field = testing::RenderPlanes(scene.planes, kViews, kSize, &labels, &disparity);
  scene.bundle.disparity = disparity;
  if (with_labels) scene.bundle.labels = labels;
  return scene;
}

nlohmann::json ReadJson(const std::filesystem::path& path) {
  return nlohmann::json::parse(lfsp::testing::ReadBytes(path));
}

// Clicking the card recolours exactly its rays in every view; every other ray is bit-identical (float .h5 output).
TEST(RecolorCliTest, ClickRecoloursTheCardAndNothingElse) {
  TempDir dir;
  const Scene scene = MakeScene(true);
  WriteBundle(scene.bundle, dir / "in.h5");
  const auto result = RunLfsp({"recolor", (dir / "in.h5").string(), "--at", "30,30", "--hue", "90", "--value", "0.8",
                               "--out", (dir / "out" / "edited.h5").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "edited.before.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "edited.after.png"));

  const Bundle edited = ReadBundle(dir / "out" / "edited.h5");
  const LightField& before = scene.bundle.light_field;
  std::size_t changed = 0;
  std::size_t card_rays = 0;
  for (std::size_t ray = 0; ray < scene.bundle.labels->size(); ++ray) {
    const bool on_card = scene.bundle.labels->data()[ray] == 1;
    card_rays += on_card ? 1 : 0;
    bool differs = false;
    for (std::size_t c = 0; c < 3; ++c)
      differs = differs || before.data()[3 * ray + c] != edited.light_field.data()[3 * ray + c];
    if (!on_card) {
      ASSERT_FALSE(differs) << "ray " << ray << " outside the card changed";
    }
    changed += differs ? 1 : 0;
  }
  EXPECT_EQ(changed, card_rays);  // a textured, non-black card: every ray changes

  const nlohmann::json summary = ReadJson(dir / "out" / "edited.summary.json");
  EXPECT_EQ(summary["selected_labels"], nlohmann::json::array({1}));
  EXPECT_EQ(summary["rays"]["changed"].get<std::size_t>(), changed);
  EXPECT_EQ(summary["rays"]["selected"].get<std::size_t>(), card_rays);
}

// Labels from a separate file and a mask selection; a views-folder output.
TEST(RecolorCliTest, MaskSelectionWithSeparateLabelsFile) {
  TempDir dir;
  Scene scene = MakeScene(true);
  WriteBundle(scene.bundle, dir / "labels.h5");  // `lfsp segment` writes a full bundle with a labels dataset
  scene.bundle.labels.reset();
  WriteBundle(scene.bundle, dir / "in.h5");
  cv::Mat mask(kSize, kSize, CV_32FC1, cv::Scalar(0.0));
  mask(cv::Rect(0, 0, kSize, 30)).setTo(1.0);  // rows 0-29: 12 of the card's 24 rows (rows 18-41)
  WriteImage(mask, dir / "mask.png");
  auto result = RunLfsp({"recolor", (dir / "in.h5").string(), "--labels", (dir / "labels.h5").string(), "--mask",
                         (dir / "mask.png").string(), "--saturation", "0", "--out", (dir / "views").string()});
  // The card has exactly 50 % of its area inside, the background (30 * 64 - 12 * 24) / (64 * 64 - 24 * 24) = 46 %:
  // neither has more than half inside, so nothing is selected: bad input.
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_NE(result.err.find("mask"), std::string::npos) << result.err;

  mask(cv::Rect(0, 0, kSize, 31)).setTo(1.0);  // one more row: the card is 13/24 inside, the background 47.5 %
  WriteImage(mask, dir / "mask.png");
  result = RunLfsp({"recolor", (dir / "in.h5").string(), "--labels", (dir / "labels.h5").string(), "--mask",
                    (dir / "mask.png").string(), "--saturation", "0", "--out", (dir / "views").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const Bundle edited = LoadLightField(dir / "views");
  EXPECT_EQ(edited.light_field.shape(), scene.bundle.light_field.shape());
  // Desaturated card: R = G = B (up to 8-bit rounding) in the corner view (0, 0), offset (-3, -3): its pixel
  // (36, 34) sees the card at centre-view position (36 - 3 * 1.5, 34 - 3 * 1.5) = (31.5, 29.5).
  const float* ray = &edited.light_field.at({0, 0}, 34, 36, 0);
  EXPECT_NEAR(ray[0], ray[1], 2.0f / 255.0f);
  EXPECT_NEAR(ray[1], ray[2], 2.0f / 255.0f);
  EXPECT_TRUE(std::filesystem::exists(dir / "views" / "summary.json"));
}

TEST(RecolorCliTest, BadInputExitsWithStatus2) {
  TempDir dir;
  const Scene scene = MakeScene(false);
  WriteBundle(scene.bundle, dir / "in.h5");
  const std::string in = (dir / "in.h5").string();
  const std::string out = (dir / "out.h5").string();
  auto result = RunLfsp({"recolor", in, "--at", "30,30", "--out", out});  // no labels anywhere
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_NE(result.err.find("lfsp: error:"), std::string::npos);
  EXPECT_NE(result.err.find("labels"), std::string::npos) << result.err;

  const Scene labelled = MakeScene(true);
  WriteBundle(labelled.bundle, dir / "labelled.h5");
  const std::string labelled_in = (dir / "labelled.h5").string();
  EXPECT_EQ(RunLfsp({"recolor", labelled_in, "--at", "30,30", "--label-ids", "1", "--out", out}).exit_status, 2);
  EXPECT_EQ(RunLfsp({"recolor", labelled_in, "--at", "30;30", "--out", out}).exit_status, 2);
  EXPECT_EQ(RunLfsp({"recolor", labelled_in, "--at", "300,30", "--out", out}).exit_status, 2);
  EXPECT_EQ(RunLfsp({"recolor", labelled_in, "--label-ids", "7", "--out", out}).exit_status, 2);
  EXPECT_EQ(RunLfsp({"recolor", labelled_in, "--label-ids", "1", "--value", "-1", "--out", out}).exit_status, 2);
  EXPECT_EQ(
      RunLfsp({"recolor", labelled_in, "--label-ids", "1", "--labels", (dir / "missing.h5").string(), "--out", out})
          .exit_status,
      2);
  EXPECT_EQ(RunLfsp({"recolor", labelled_in, "--label-ids", "1", "--out", labelled_in}).exit_status, 2);
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A focal stack, the all-in-focus image and the sheared light field, checked against the scene.
TEST(RefocusCliTest, StackAllInFocusAndShear) {
  TempDir dir;
  const Scene scene = MakeScene(true);
  WriteBundle(scene.bundle, dir / "in.h5");
  const auto result =
      RunLfsp({"refocus", (dir / "in.h5").string(), "--disparities", "-1,1.5", "--all-in-focus", "--shear", "1.5",
               "--out-lf", (dir / "sheared.h5").string(), "--bit-depth", "16", "--out", (dir / "refocus").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const nlohmann::json summary = ReadJson(dir / "refocus" / "summary.json");
  ASSERT_EQ(summary["focal_stack"].size(), 2u);
  EXPECT_EQ(summary["focal_stack"][1]["file"], "refocus_01_d+1.500.png");
  EXPECT_GT(summary["all_in_focus"]["psnr_vs_centre_view_db"].get<double>(), 35.0);

  // The all-in-focus PNG is the centre view (16-bit, so quantisation is negligible).
  const cv::Mat centre = scene.bundle.light_field.View(scene.bundle.light_field.shape().Centre());
  const cv::Mat all_in_focus = ReadImage(dir / "refocus" / "all_in_focus.png").pixels;
  EXPECT_GT(Psnr(centre, all_in_focus), 35.0);
  // Focused on the card, the card is sharp and the background is not (33.9 dB measured on the card: bilinear
  // interpolation error, largest on the card's edge pixels, which blend with the background).
  const cv::Mat at_card = ReadImage(dir / "refocus" / "refocus_01_d+1.500.png").pixels;
  const cv::Mat card = scene.bundle.labels->View(scene.bundle.labels->shape().Centre()) == 1;
  EXPECT_GT(Psnr(centre, at_card, card), 32.0);
  EXPECT_LT(Psnr(centre, at_card, ~card), 25.0);

  // Sheared by the card's disparity, the card is aligned across views and the disparity map moved by -1.5.
  const Bundle sheared = ReadBundle(dir / "sheared.h5");
  ASSERT_TRUE(sheared.disparity.has_value());
  EXPECT_FLOAT_EQ(sheared.disparity->at(30, 30), 0.0f);
  EXPECT_FLOAT_EQ(sheared.disparity->at(5, 5), -2.5f);
  cv::Mat inner_card(kSize, kSize, CV_8UC1, cv::Scalar(0));
  inner_card(cv::Rect(22, 20, 20, 20)).setTo(255);
  // View (0, 6) moved by (-4.5, 4.5) px: a half-pixel bilinear shift, the blurriest case (33.7 dB measured).
  EXPECT_GT(Psnr(sheared.light_field.View({3, 3}), sheared.light_field.View({0, 6}), inner_card), 31.0);
  ASSERT_TRUE(sheared.labels.has_value());
  EXPECT_EQ(sheared.labels->at({0, 6}, 30, 30), 1);
}

TEST(RefocusCliTest, BadInputExitsWithStatus2) {
  TempDir dir;
  Scene scene = MakeScene(false);
  scene.bundle.disparity.reset();
  WriteBundle(scene.bundle, dir / "in.h5");
  const std::string in = (dir / "in.h5").string();
  const std::string out = (dir / "r").string();
  EXPECT_EQ(RunLfsp({"refocus", in, "--out", out}).exit_status, 2);                    // nothing to do
  EXPECT_EQ(RunLfsp({"refocus", in, "--stack", "4", "--out", out}).exit_status, 2);    // no range known
  EXPECT_EQ(RunLfsp({"refocus", in, "--all-in-focus", "--out", out}).exit_status, 2);  // no disparity map
  EXPECT_EQ(RunLfsp({"refocus", in, "--shear", "1", "--out", out}).exit_status, 2);    // no --out-lf
  EXPECT_EQ(RunLfsp({"refocus", in, "--disparities", "1", "--interpolation", "nearest", "--out", out}).exit_status, 2);
  EXPECT_EQ(RunLfsp({"refocus", (dir / "missing.h5").string(), "--disparities", "1", "--out", out}).exit_status, 2);
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_EQ(RunLfsp({"refocus", in, "--stack", "3", "--range", "-1,1", "--out", out}).exit_status, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "r" / "refocus_02_d+1.000.png"));
}

}  // namespace
}  // namespace lfsp::edit
