// `lfsp pipeline` end to end through the CLI, on a small simulated scene with ground truth.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/pfm.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ReadBytes;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

class PipelineEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = new TempDir();
    const auto simulated = RunLfsp({"-q", "simulate", "--ideal-only", "--scene", "planes", "--views", "5", "--size",
                                    "96x80", "--out", (temp_->path() / "scene").string()});
    ASSERT_EQ(simulated.exit_status, 0) << simulated.err;
    input_ = temp_->path() / "scene" / "ideal.h5";
    result_ = new lfsp::testing::CommandResult(
        RunLfsp({"pipeline", input_.string(), "--out", (temp_->path() / "run").string(), "--size", "12", "--recolor",
                 "at=48,40;hue=120"}));
  }
  static void TearDownTestSuite() {
    delete result_;
    delete temp_;
  }
  static fs::path Run() { return temp_->path() / "run"; }

  static TempDir* temp_;
  static fs::path input_;
  static lfsp::testing::CommandResult* result_;
};

TempDir* PipelineEndToEnd::temp_ = nullptr;
fs::path PipelineEndToEnd::input_;
lfsp::testing::CommandResult* PipelineEndToEnd::result_ = nullptr;

TEST_F(PipelineEndToEnd, WritesEveryIntermediateInTheProjectFormats) {
  ASSERT_EQ(result_->exit_status, 0) << result_->err;
  EXPECT_NE(result_->out.find("report.html"), std::string::npos);
  const DisparityMap disparity = ReadPfm(Run() / "disparity.pfm");
  EXPECT_EQ(disparity.width(), 96);
  EXPECT_EQ(disparity.height(), 80);
  const Bundle segmentation = ReadBundle(Run() / "segmentation.h5");
  ASSERT_TRUE(segmentation.labels.has_value());
  EXPECT_EQ(segmentation.labels->shape().nu, 5);
  const Bundle recoloured = ReadBundle(Run() / "recolored.h5");
  EXPECT_EQ(recoloured.light_field.shape(), segmentation.light_field.shape());
  EXPECT_TRUE(fs::exists(Run() / "recolored.after.png"));
  EXPECT_TRUE(fs::exists(Run() / "segmentation.overlay_centre.png"));
  EXPECT_TRUE(fs::exists(Run() / "disparity.png"));
  EXPECT_FALSE(fs::is_empty(Run() / "focal_stack"));
}

TEST_F(PipelineEndToEnd, SummaryHasMetricsAgainstGroundTruthAndTimingsThatAddUp) {
  ASSERT_EQ(result_->exit_status, 0) << result_->err;
  const auto summary = nlohmann::json::parse(ReadBytes(Run() / "summary.json"));
  ASSERT_TRUE(summary.contains("metrics"));
  EXPECT_TRUE(summary["metrics"]["depth"]["all"].contains("badpix_0.07"));
  EXPECT_DOUBLE_EQ(summary["metrics"]["segmentation"]["elr"].get<double>(), 1.0);
  EXPECT_TRUE(summary["metrics"]["segmentation"].contains("boundary_recall"));
  double stages = 0.0;
  for (const auto& [stage, seconds] : summary["timings"].items()) stages += seconds.get<double>();
  const double wall = summary["wall_seconds"].get<double>();
  EXPECT_GT(stages, 0.9 * wall) << "stage timings must account for the wall time";
  EXPECT_LE(stages, wall);
  EXPECT_GT(summary["recolor"]["changed_rays"].get<long>(), 0);
  // Every summary names the lfsp that wrote it: the same string as `lfsp --version` (issue 47).
  ASSERT_TRUE(summary.contains("version"));
  EXPECT_EQ(RunLfsp({"--version"}).out, "lfsp " + summary["version"].get<std::string>() + "\n");
}

TEST_F(PipelineEndToEnd, ReportIsSelfContainedWithEverySection) {
  ASSERT_EQ(result_->exit_status, 0) << result_->err;
  const std::string html = ReadBytes(Run() / "report.html");
  for (const char* expected : {"Centre view", "Sweep through the views", "Estimated disparity", "LFSP boundaries",
                               "Horizontal EPI", "Vertical EPI", "Recolouring", "Focal stack", "Metrics", "Timings"})
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  EXPECT_EQ(html.find("src=\"http"), std::string::npos) << "the report must not load anything from the network";
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);
  EXPECT_EQ(html.find("Decoded against the ideal light field"), std::string::npos)
      << "an ideal light field has no decode to compare";
}

// A simulated capture with its ground truth beside it: the summary and the report compare the decode with the ideal
// light field (bundled mini-F01 sample, 9x9 views of 80x80: measured 61 views registered, worst 0.117 px, centre
// view PSNR 23.7 dB; the small views' sharp occluder edges limit both).
TEST(PipelineOnACapture, ComparesTheDecodeWithTheIdealLightField) {
  TempDir temp;
  const fs::path run = temp.path() / "run";
  const auto result =
      RunLfsp({"pipeline", (lfsp::testing::SourceDir() / "samples" / "mini-f01" / "capture.lfp").string(), "--out",
               run.string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const auto summary = nlohmann::json::parse(ReadBytes(run / "summary.json"));
  const auto& comparison = summary["metrics"]["decode_vs_truth"];
  EXPECT_GE(comparison["registration"]["views_registered"].get<int>(), 40);
  EXPECT_EQ(comparison["registration"]["views"].size(), comparison["registration"]["views_registered"].get<size_t>());
  EXPECT_LT(comparison["registration"]["worst_shift_px"].get<double>(), 0.2);
  EXPECT_GT(comparison["centre_view"]["psnr_db"].get<double>(), 20.0);
  const std::string html = ReadBytes(run / "report.html");
  for (const char* expected : {"Decoded against the ideal light field", "Centre-view error", "Per-view registration"})
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  // For people (issue 47): every figure named in words with its meaning (metric_descriptions.cc), the per-view
  // shifts drawn as a plot rather than dumped, the raw JSON a link away.
  for (const char* expected : {"Bad pixels at 0.07 px", "Self-similarity", "Worst view shift", "<svg class=\"plot\"",
                               "href=\"summary.json\"", "<code class=\"key\">depth.all.badpix_0.07</code>"})
    EXPECT_NE(html.find(expected), std::string::npos) << expected;
  EXPECT_EQ(html.find("class=\"undescribed\""), std::string::npos) << "a metric the report does not describe";
  EXPECT_EQ(html.find("\"dx\""), std::string::npos) << "per-view shifts dumped as JSON";
}

TEST(PipelineBadInput, BadRecolorSpecFailsBeforeWritingAnything) {
  TempDir temp;
  const auto result =
      RunLfsp({"pipeline", "/nonexistent.h5", "--out", (temp.path() / "run").string(), "--recolor", "hue=oops"});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_FALSE(fs::exists(temp.path() / "run"));
}

TEST(PipelineBadInput, RefusesToWriteIntoAForeignFolder) {
  TempDir temp;
  fs::create_directories(temp.path() / "mine");
  lfsp::testing::WriteBytes(temp.path() / "mine" / "notes.txt", "keep");
  const auto result = RunLfsp({"pipeline", "/nonexistent.h5", "--out", (temp.path() / "mine").string()});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_EQ(ReadBytes(temp.path() / "mine" / "notes.txt"), "keep");
}

}  // namespace
}  // namespace lfsp
