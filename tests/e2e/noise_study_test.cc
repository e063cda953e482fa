// `lfsp noise-study` on a tiny configuration: every output is written, every method is scored at every level of
// both kinds of noise, and the results are the study's own (LFSP keeps a full effective label ratio).

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ReadBytes;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

TEST(NoiseStudy, WritesCsvSummaryAndPlotsForEveryLevelAndMethod) {
  TempDir temp;
  const fs::path out = temp.path() / "study";
  const auto result = RunLfsp({"-q", "noise-study", "--out", out.string(), "--views", "5", "--width", "48", "--height",
                               "48", "--size", "10", "--sigmas", "0,0.05", "--exposures", "0.7,0.1", "--no-lsc"});
  ASSERT_EQ(result.exit_status, 0) << result.err;

  std::istringstream csv(ReadBytes(out / "noise_study.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("noise,level,noise_measure,method", 0), 0u) << line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 2 * 2 * 2) << "2 noise kinds x 2 levels x 2 methods";

  const auto summary = nlohmann::json::parse(ReadBytes(out / "summary.json"));
  ASSERT_EQ(summary["results"].size(), 8u);
  for (const auto& entry : summary["results"]) {
    EXPECT_TRUE(entry["metrics"].contains("self_similarity")) << entry.dump();
    EXPECT_TRUE(entry["metrics"].contains("boundary_recall")) << entry.dump();
    if (entry["method"] == "lfsp") {
      EXPECT_DOUBLE_EQ(entry["metrics"]["elr"].get<double>(), 1.0);
    }
  }
  EXPECT_TRUE(summary["degradation"]["image"].contains("lfsp"));
  for (const char* plot : {"plot_image_self_similarity.png", "plot_lowlight_elr.png"})
    EXPECT_GT(fs::file_size(out / plot), 1000u) << plot;
  EXPECT_FALSE(fs::exists(out / "captures")) << "intermediate captures are removed";
}

TEST(NoiseStudy, BadLevelListIsBadInput) {
  TempDir temp;
  const auto result = RunLfsp({"noise-study", "--out", (temp.path() / "s").string(), "--sigmas", "0,abc"});
  EXPECT_EQ(result.exit_status, 2);
}

}  // namespace
}  // namespace lfsp
