// One way to run a stage (issue 14): `lfsp pipeline` on the bundled mini-Illum capture, then the single commands
// (decode, depth, segment, refocus, recolor) with the same inputs and options; every file the pipeline's stages
// wrote must be byte for byte what the command wrote. Summaries differ by design (timings, the command name), so
// only their parameters are compared.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::ReadBytes;
using testing::RunLfsp;
using testing::TempDir;

// The range is given to both, so that neither estimates it (the pipeline would take the simulator's ground truth).
const std::vector<std::string> kRange = {"--dmin", "-1.2", "--dmax", "1.4"};
constexpr const char* kRecolorPoint = "40,30";

class StageEquivalence : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = new TempDir();
    capture_ = testing::SourceDir() / "samples" / "mini-illum" / "capture.LFR";
    std::vector<std::string> pipeline = {"-q",
                                         "pipeline",
                                         capture_.string(),
                                         "--out",
                                         Run().string(),
                                         "--recolor",
                                         std::string("at=") + kRecolorPoint + ";hue=120",
                                         "--focal-stack",
                                         "3"};
    pipeline.insert(pipeline.end(), kRange.begin(), kRange.end());
    pipeline_status_ = RunLfsp(pipeline).exit_status;
  }
  static void TearDownTestSuite() { delete temp_; }
  static fs::path Run() { return temp_->path() / "run"; }
  static fs::path Single() { return temp_->path() / "single"; }

  // Runs one command and requires it to succeed.
  static void Command(const std::vector<std::string>& arguments) {
    std::vector<std::string> quiet = {"-q"};
    quiet.insert(quiet.end(), arguments.begin(), arguments.end());
    const testing::CommandResult result = RunLfsp(quiet);
    ASSERT_EQ(result.exit_status, 0) << arguments.front() << ": " << result.err;
  }

  static void ExpectSameBytes(const fs::path& from_pipeline, const fs::path& from_command) {
    ASSERT_TRUE(fs::exists(from_pipeline)) << from_pipeline;
    ASSERT_TRUE(fs::exists(from_command)) << from_command;
    EXPECT_TRUE(ReadBytes(from_pipeline) == ReadBytes(from_command))
        << from_pipeline << " differs from " << from_command;
  }

  static nlohmann::json Json(const fs::path& path) { return nlohmann::json::parse(ReadBytes(path)); }

  static TempDir* temp_;
  static fs::path capture_;
  static int pipeline_status_;
};

TempDir* StageEquivalence::temp_ = nullptr;
fs::path StageEquivalence::capture_;
int StageEquivalence::pipeline_status_ = -1;

TEST_F(StageEquivalence, PipelineWritesWhatTheSingleCommandsWrite) {
  ASSERT_EQ(pipeline_status_, 0);
  fs::create_directories(Single());
  const std::string decoded = (Single() / "decoded.h5").string();
  // The pipeline slices only the views its stages keep, as `decode --views 0` does.
  Command({"decode", capture_.string(), "--views", "0", "--out", decoded});

  std::vector<std::string> depth = {"depth", decoded, "--out", (Single() / "disparity.pfm").string()};
  depth.insert(depth.end(), kRange.begin(), kRange.end());
  Command(depth);
  for (const char* name : {"disparity.pfm", "disparity.png", "disparity_confidence.pfm"})
    ExpectSameBytes(Run() / name, Single() / name);
  EXPECT_EQ(Json(Run() / "disparity.summary.json")["parameters"],
            Json(Single() / "disparity.summary.json")["parameters"]);

  // The pipeline records its disparity by its final path; the command is given that same path.
  Command({"segment", decoded, "--disparity", (Run() / "disparity.pfm").string(), "--out",
           (Single() / "segmentation.h5").string()});
  for (const char* name : {"segmentation.h5", "segmentation.planes.json", "segmentation.overlay_centre.png",
                           "segmentation.overlay_epi_h.png", "segmentation.overlay_epi_v.png"})
    ExpectSameBytes(Run() / name, Single() / name);

  const nlohmann::json range = Json(Run() / "summary.json")["disparity_range"];
  const std::string stack_range = range["min"].dump() + "," + range["max"].dump();
  const std::string segmentation = (Run() / "segmentation.h5").string();
  Command(
      {"refocus", segmentation, "--stack", "3", "--range", stack_range, "--out", (Single() / "focal_stack").string()});
  std::size_t slices = 0;
  for (const auto& entry : fs::directory_iterator(Run() / "focal_stack")) {
    if (entry.path().extension() != ".png") continue;
    ExpectSameBytes(entry.path(), Single() / "focal_stack" / entry.path().filename());
    ++slices;
  }
  EXPECT_EQ(slices, 3u);

  Command(
      {"recolor", segmentation, "--at", kRecolorPoint, "--hue", "120", "--out", (Single() / "recolored.h5").string()});
  for (const char* name : {"recolored.h5", "recolored.before.png", "recolored.after.png"})
    ExpectSameBytes(Run() / name, Single() / name);
  EXPECT_EQ(Json(Run() / "recolored.summary.json")["rays"], Json(Single() / "recolored.summary.json")["rays"]);
}

}  // namespace
}  // namespace lfsp
