// Exports people ask for (issue 17, item 5): views as 16-bit TIFF, a view-sweep animation (GIF, MP4), disparity as a
// 16-bit PNG with its range in text chunks. Each is read back and checked.

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/visualize.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

LightField Sample() {
  LightField light_field({3, 3, 32, 24, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i)
    light_field.data()[i] = static_cast<float>((i * 7919) % 65536) / 65535.0f;
  return light_field;
}

int Subimages(const fs::path& path, int& width, int& height) {
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) return 0;
  width = input->spec().width;
  height = input->spec().height;
  int count = 1;
  while (input->seek_subimage(count, 0)) ++count;
  return count;
}

TEST(Exports, ViewsAsSixteenBitTiff) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = Sample();
  SaveLightField(bundle, temp / "views", 16, ".tif");
  ASSERT_TRUE(fs::exists(temp / "views" / "input_Cam004.tif"));
  const ImageHeader header = ReadImageHeader(temp / "views" / "input_Cam004.tif");
  EXPECT_EQ(header.bit_depth, 16);
  const LightField back = LoadLightField(temp / "views").light_field;
  for (std::size_t i = 0; i < back.size(); ++i) ASSERT_NEAR(back.data()[i], bundle.light_field.data()[i], 0.6 / 65535);
}

TEST(Exports, ViewSweepAsGifAndMp4) {
  TempDir temp;
  const LightField light_field = Sample();
  const std::vector<cv::Mat> frames = ViewSweepFrames(light_field);
  ASSERT_EQ(frames.size(), 6u);  // the middle row (3), then the middle column (3)
  WriteAnimation(frames, temp / "sweep.gif", 8.0);
  WriteAnimation(frames, temp / "sweep.mp4", 8.0);
  for (const char* name : {"sweep.gif", "sweep.mp4"}) {
    SCOPED_TRACE(name);
    int width = 0, height = 0;
    EXPECT_EQ(Subimages(temp / name, width, height), 6);
    EXPECT_EQ(width, 32);
    EXPECT_EQ(height, 24);
  }
  EXPECT_THROW(WriteAnimation(frames, temp / "sweep.avi", 8.0), Error);
  EXPECT_FALSE(fs::exists(temp / "sweep.avi"));
}

TEST(Exports, DisparityAsSixteenBitPng) {
  TempDir temp;
  DisparityMap disparity(40, 30);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x)
      disparity.at(y, x) = -2.5f + 0.1f * static_cast<float>(x) + 0.01f * static_cast<float>(y);
  disparity.at(3, 4) = NAN;
  WriteDisparityPng16(disparity, temp / "d.png");
  const ImageFile png = ReadImage(temp / "d.png");
  ASSERT_EQ(png.bit_depth, 16);
  const double low = std::stod(png.text.at("lfsp:disparity_min")), high = std::stod(png.text.at("lfsp:disparity_max"));
  EXPECT_NEAR(low, -2.5, 1e-6);
  EXPECT_NEAR(high, -2.5 + 3.9 + 0.29, 1e-5);
  EXPECT_EQ(png.pixels.at<float>(3, 4), 0.0f);  // no disparity
  for (const auto& [y, x] : {std::pair{0, 0}, std::pair{29, 39}, std::pair{12, 17}}) {
    const double value = std::round(png.pixels.at<float>(y, x) * 65535.0);
    EXPECT_NEAR(low + (value - 1) / 65534.0 * (high - low), disparity.at(y, x), (high - low) / 65534.0);
  }
}

}  // namespace
}  // namespace lfsp
