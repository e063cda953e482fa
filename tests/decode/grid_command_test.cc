// `lfsp grid` end to end: a capture's lattice from the capture itself, as JSON and as a centre table; bad input
// exits 2 with one line naming the file and writes nothing (issue 13).

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include <opencv2/core.hpp>

#include "lfsp/core/image_io.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::RunLfsp;
using testing::SourceDir;
using testing::TempDir;

TEST(GridCommand, FindsTheSampleCapturesLatticeAndWritesItsCentres) {
  const fs::path capture = SourceDir() / "samples" / "mini-illum" / "capture.LFR";
  ASSERT_TRUE(fs::exists(capture)) << testing::kMissingSample;
  TempDir dir;
  const auto result = RunLfsp(
      {"grid", capture.string(), "--out", (dir / "grid.json").string(), "--centres", (dir / "centres.csv").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_NE(result.out.find("capture periodicity"), std::string::npos) << result.out;
  const nlohmann::json document = nlohmann::json::parse(testing::ReadBytes(dir / "grid.json"));
  const nlohmann::json& grid = document["grid"];
  EXPECT_EQ(document["kind"], "capture");
  // The sample's simulated lattice: Illum optics on 1024 x 768, 70 x 60 usable lenses of 14.29 px.
  EXPECT_EQ(grid["columns"], 70);
  EXPECT_EQ(grid["rows"], 60);
  EXPECT_NEAR(grid["spacing_x"].get<double>(), 14.29, 0.02);
  std::ifstream csv(dir / "centres.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "row,col,x,y");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 70 * 60);
}

TEST(GridCommand, AnImageWithoutALatticeExits2AndWritesNothing) {
  TempDir dir;
  cv::Mat noise(600, 600, CV_8U);
  cv::randu(noise, 0, 255);
  WriteImage(noise, dir / "noise.png");
  const fs::path out = dir / "grid.json";
  auto result = RunLfsp({"grid", (dir / "noise.png").string(), "--out", out.string()});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_NE(result.err.find("noise.png: lenslet grid: the image shows no micro-lens lattice"), std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(out));
  // A colour picture is not a raw Bayer image.
  cv::Mat colour(64, 64, CV_8UC3, cv::Scalar(10, 200, 30));
  WriteImage(colour, dir / "colour.png");
  result = RunLfsp({"grid", (dir / "colour.png").string(), "--out", out.string()});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_NE(result.err.find("colour.png: a raw Bayer image has one channel"), std::string::npos) << result.err;
  EXPECT_FALSE(fs::exists(out));
  // An unknown camera is refused before any work.
  result = RunLfsp({"grid", (dir / "noise.png").string(), "--camera", "f02", "--out", out.string()});
  EXPECT_EQ(result.exit_status, 2);
  EXPECT_NE(result.err.find("--camera 'f02'"), std::string::npos) << result.err;
}

// `info --camera` reads a plain raw image as decode would: levels, Bayer pattern, codes per phase.
TEST(GridCommand, InfoDescribesAPlainRawImage) {
  TempDir dir;
  cv::Mat mosaic(64, 64, CV_16U);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) mosaic.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(200 + 100 * (x % 2));
  WriteImage(mosaic, dir / "raw.png", 16);
  const auto result = RunLfsp({"info", (dir / "raw.png").string(), "--camera", "f01"});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  EXPECT_NE(result.out.find("plain raw image (16-bit png)"), std::string::npos) << result.out;
  // Codes up to 300 fit under the F01's 4095 white level: a sensor dump, read with the camera's levels.
  EXPECT_NE(result.out.find("the camera's levels"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("BGGR"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("phase 1      codes 300 .. 300"), std::string::npos) << result.out;
}

}  // namespace
}  // namespace lfsp
