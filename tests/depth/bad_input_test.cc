// Bad input fails with lfsp::Error (library) or exit status 2 and one line (CLI), and writes no output; plus the CLI
// happy path on a small views folder with ground truth beside it.

#include <gtest/gtest.h>

#include <algorithm>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/depth/depth_estimator.h"
#include "synthetic_light_field.h"
#include "test_support.h"

namespace lfsp::depth {
namespace {

using lfsp::testing::CommandResult;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

testing::ShiftLightField SmallScene() {
  testing::ShiftScene scene;
  scene.views = 7;
  scene.size = 64;
  return testing::MakeShiftLightField(scene);
}

TEST(DepthBadInput, LibraryRejectsUnusableLightFields) {
  testing::ShiftLightField scene = SmallScene();
  DepthOptions options;
  options.labels = 2;
  EXPECT_THROW(EstimateDepth(scene.light_field, options), Error);

  // No recorded range and nothing to measure one on (flat views).
  LightField flat(scene.light_field.shape());
  std::fill(flat.data(), flat.data() + flat.size(), 0.5f);
  EXPECT_THROW(EstimateDepth(flat, {}), Error);
  DepthOptions inverted;
  inverted.range = DisparityRange{1.0f, -1.0f};
  EXPECT_THROW(EstimateDepth(scene.light_field, inverted), Error);

  LightFieldShape grey_shape = scene.light_field.shape();
  grey_shape.channels = 1;
  LightField grey(grey_shape);
  grey.metadata = scene.light_field.metadata;
  EXPECT_THROW(EstimateDepth(grey, {}), Error);

  EXPECT_THROW(EstimateDepth(LightField(), {}), Error);
}

TEST(DepthBadInput, CliReportsMissingAndMismatchedFiles) {
  TempDir dir;
  const auto out = dir / "disp.pfm";
  CommandResult missing = RunLfsp({"depth", (dir / "no_such_folder").string(), "--out", out.string()});
  EXPECT_EQ(missing.exit_status, 2);
  EXPECT_NE(missing.err.find("no_such_folder"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(out));

  WritePfm(DisparityMap(32, 32, 0.0f), dir / "a.pfm");
  WritePfm(DisparityMap(32, 30, 0.0f), dir / "b.pfm");
  CommandResult mismatch = RunLfsp({"evaluate", "depth", (dir / "a.pfm").string(), "--gt", (dir / "b.pfm").string()});
  EXPECT_EQ(mismatch.exit_status, 2);
  EXPECT_NE(mismatch.err.find("32x30"), std::string::npos) << mismatch.err;

  lfsp::testing::WriteBytes(dir / "broken.pfm", "Pf\n32 32\n-1.0\nshort");
  CommandResult broken =
      RunLfsp({"evaluate", "depth", (dir / "broken.pfm").string(), "--gt", (dir / "a.pfm").string()});
  EXPECT_EQ(broken.exit_status, 2);
  EXPECT_NE(broken.err.find("broken.pfm"), std::string::npos) << broken.err;
}

TEST(DepthBadInput, CliRejectsAViewOfTheWrongSize) {
  TempDir dir;
  testing::ShiftLightField scene = SmallScene();
  Bundle bundle;
  bundle.light_field = scene.light_field;
  const auto folder = dir / "views";
  SaveLightField(bundle, folder);
  WriteImage(cv::Mat(20, 20, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5)), folder / "input_Cam003.png");
  CommandResult result = RunLfsp({"depth", folder.string(), "--out", (dir / "d.pfm").string()});
  EXPECT_EQ(result.exit_status, 2) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "d.pfm"));
}

TEST(DepthCli, WritesDisparityPreviewConfidenceAndSummaryWithMetrics) {
  TempDir dir;
  testing::ShiftLightField scene = SmallScene();
  Bundle bundle;
  bundle.light_field = scene.light_field;
  bundle.disparity = scene.disparity;
  const auto folder = dir / "views";
  SaveLightField(bundle, folder);
  const auto out = dir / "disp.pfm";
  CommandResult result = RunLfsp({"depth", folder.string(), "--out", out.string(), "--labels", "40"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const DisparityMap disparity = ReadPfm(out);
  EXPECT_EQ(disparity.width(), 64);
  EXPECT_TRUE(std::filesystem::exists(dir / "disp.png"));
  EXPECT_EQ(ReadPfm(dir / "disp_confidence.pfm").width(), 64);
  std::ifstream summary_file(dir / "disp.summary.json");
  ASSERT_TRUE(summary_file.good());
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  EXPECT_EQ(summary["parameters"]["labels"], 40);
  // The ground truth beside the views (disparity.pfm) is used for metrics. Measured on this 7x7x64x64 scene through
  // 8-bit PNG views, 40 labels, 15 px frame: BadPix 0.07 14.9 %, MSE x100 2.8 (a broken method scores ~90 %).
  ASSERT_TRUE(summary.contains("metrics_vs_input_ground_truth"));
  EXPECT_LT(summary["metrics_vs_input_ground_truth"]["all"]["badpix_0.07"].get<double>(), 25.0);
  EXPECT_LT(summary["metrics_vs_input_ground_truth"]["all"]["mse_x100"].get<double>(), 6.0);

  CommandResult evaluate = RunLfsp({"evaluate", "depth", out.string(), "--gt", (folder / "disparity.pfm").string(),
                                    "--json", (dir / "metrics.json").string()});
  ASSERT_EQ(evaluate.exit_status, 0) << evaluate.err;
  const nlohmann::json printed = nlohmann::json::parse(evaluate.out);
  EXPECT_DOUBLE_EQ(printed["all"]["badpix_0.07"].get<double>(),
                   summary["metrics_vs_input_ground_truth"]["all"]["badpix_0.07"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(dir / "metrics.json"));
}

}  // namespace
}  // namespace lfsp::depth
