// `lfsp noise-study` on a tiny configuration (the mini-Illum sensor instead of the default full Illum): every output
// is written, every method is scored at every level of both kinds of noise, the low-light levels keep the reference
// brightness, and LFSP keeps a full effective label ratio.

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
  const auto result = RunLfsp({"-q",
                               "noise-study",
                               "--out",
                               out.string(),
                               "--views",
                               "5",
                               "--width",
                               "48",
                               "--height",
                               "48",
                               "--size",
                               "10",
                               "--sigmas",
                               "0,0.05",
                               "--camera",
                               "mini-illum",
                               "--capture-views",
                               "9",
                               "--capture-size",
                               "8",
                               "--exposures",
                               "0.7,0.1",
                               "--no-lsc"});
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

  // Low light is brought back to the reference brightness in linear light: the dim capture is noisier, not brighter
  // or blown out (a gain applied after the sRGB curve clipped about half of it to white).
  const auto& brightness = summary["lowlight_brightness"];
  ASSERT_EQ(brightness.size(), 2u);
  const double reference = brightness[0]["mean"].get<double>();
  for (const auto& level : brightness) {
    EXPECT_EQ(level["light_field"], "9x9 views of 60x80x3") << "central 9x9 of the 15x15 decode";
    EXPECT_LT(level["clipped_fraction"].get<double>(), 0.01) << level.dump();
    EXPECT_NEAR(level["mean"].get<double>(), reference, 0.05 * reference) << level.dump();
  }
  for (const char* plot : {"plot_image_self_similarity.png", "plot_lowlight_elr.png"})
    EXPECT_GT(fs::file_size(out / plot), 1000u) << plot;
  EXPECT_FALSE(fs::exists(out / "captures")) << "intermediate captures are removed";
}

TEST(NoiseStudy, BadLevelListIsBadInput) {
  TempDir temp;
  const auto result = RunLfsp({"noise-study", "--out", (temp.path() / "s").string(), "--sigmas", "0,abc"});
  EXPECT_EQ(result.exit_status, 2);
}

TEST(NoiseStudy, EvenCentralViewCountIsRefusedBeforeAnyWork) {
  TempDir temp;
  const auto result = RunLfsp({"noise-study", "--out", (temp.path() / "s").string(), "--capture-views", "8"});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_NE(result.err.find("--capture-views"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace lfsp
