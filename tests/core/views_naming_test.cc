// Views folders named the way other tools name them (issue 17, item 1): the layout is detected from the names, the
// angular size comes from them, and which index moves the view horizontally is checked from the images themselves.

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/registration.h"
#include "lfsp/core/views_folder.h"
#include "lfsp/core/views_naming.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// The image motion between the views `k` steps left and right of the centre, and between those above and below
// (phase correlation: robust to the shifts of several pixels a wide baseline gives).
struct Motion {
  cv::Point2d across_columns;
  cv::Point2d across_rows;
};

Motion MotionBetweenViews(const LightField& light_field, int k) {
  const ViewIndex c = light_field.shape().Centre();
  const auto grey = [&](int du, int dv) { return GreyOf(light_field.View({c.u + du, c.v + dv})); };
  cv::Mat window;
  cv::createHanningWindow(window, grey(0, 0).size(), CV_32F);
  return {cv::phaseCorrelate(grey(-k, 0), grey(k, 0), window), cv::phaseCorrelate(grey(0, -k), grey(0, k), window)};
}

// Moving along u (a column index) must move the image horizontally, and along v vertically.
void ExpectColumnsMoveHorizontally(const LightField& light_field, int k) {
  const Motion m = MotionBetweenViews(light_field, k);
  EXPECT_GT(std::abs(m.across_columns.x), 0.5) << "the scene barely moves between the views";
  EXPECT_GT(std::abs(m.across_columns.x), 3.0 * std::abs(m.across_columns.y));
  EXPECT_GT(std::abs(m.across_rows.y), 3.0 * std::abs(m.across_rows.x));
  ::testing::Test::RecordProperty(
      "motion", std::to_string(m.across_columns.x) + "," + std::to_string(m.across_columns.y) + " / " +
                    std::to_string(m.across_rows.x) + "," + std::to_string(m.across_rows.y));
}

TEST(ViewsNaming, IllumFieldRowColumnFrom3) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path folder = data / "lytro_views" / "illum_field";
  const ViewsLayout layout = FindViewsLayout(folder);
  EXPECT_EQ(layout.naming, "<row>_<col>");
  EXPECT_EQ(layout.nu, 9);
  EXPECT_EQ(layout.nv, 9);
  EXPECT_EQ(layout.files.front().filename(), "3_3.png");
  EXPECT_EQ(layout.files[1].filename(), "3_4.png");  // the second number is the column
  const LightField light_field = ReadViewsFolder(folder);
  EXPECT_EQ(light_field.shape().width, 625);
  EXPECT_EQ(light_field.shape().height, 434);
  ExpectColumnsMoveHorizontally(light_field, 3);
}

TEST(ViewsNaming, LfToolboxIndexColumnRow) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path folder = data / "lytro_views" / "f01_lftoolbox" / "IMG_0001";
  const ViewsLayout layout = FindViewsLayout(folder);
  EXPECT_EQ(layout.naming, "LFToolbox <index>_<column>_<row>");
  EXPECT_EQ(layout.nu, 10);
  EXPECT_EQ(layout.nv, 10);
  // Camera 1 is row 1, column 2 (a = 2, b = 1): index 20 in the snake order (b runs 1..10 for a = 1, back for a = 2).
  EXPECT_EQ(layout.files[1].filename(), "IMG_0001_020_02_01.png");
  ExpectColumnsMoveHorizontally(ReadViewsFolder(folder), 3);
}

TEST(ViewsNaming, CheckerboardViewPrefix) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path folder = data / "lytro_views" / "f01_checkerboard";
  const ViewsLayout layout = FindViewsLayout(folder);
  EXPECT_EQ(layout.nu, 7);
  EXPECT_EQ(layout.nv, 7);
  EXPECT_EQ(layout.files[1].filename(), "view_1_2.png");
  ExpectColumnsMoveHorizontally(ReadViewsFolder(folder), 2);
}

// Synthetic folders: EPINET-style names with a scene number, an explicit pattern, and what is refused.
LightField Small() {
  LightField light_field({3, 2, 8, 6, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i) light_field.data()[i] = static_cast<float>(i % 97) / 97.0f;
  return light_field;
}

void WriteNamed(const LightField& light_field, const fs::path& folder, const std::string& format, int base) {
  fs::create_directories(folder);
  for (int v = 0; v < light_field.shape().nv; ++v)
    for (int u = 0; u < light_field.shape().nu; ++u) {
      char name[64];
      std::snprintf(name, sizeof name, format.c_str(), v + base, u + base);
      WriteImage(light_field.View({u, v}), folder / name, 8);
    }
}

TEST(ViewsNaming, EpinetNamesAndPatterns) {
  TempDir temp;
  const LightField original = Small();  // 3 columns x 2 rows
  WriteNamed(original, temp / "epinet", "2067_%02d_%02d.png", 1);
  const LightField read = ReadViewsFolder(temp / "epinet");
  ASSERT_EQ(read.shape().nu, 3);
  ASSERT_EQ(read.shape().nv, 2);
  EXPECT_NEAR(read.at({2, 1}, 3, 4, 1), original.at({2, 1}, 3, 4, 1), 1.0 / 255);

  // Column first in the name: only a pattern says so.
  WriteNamed(original, temp / "swapped", "cam-%d-%d.png", 0);  // really row, column
  const LightField by_pattern = ReadViewsFolder(temp / "swapped", "cam-{row}-{col}.png");
  EXPECT_EQ(by_pattern.shape().nu, 3);
  EXPECT_THROW(ReadViewsFolder(temp / "swapped", "cam-{row}.png"), Error);  // no {col}
  EXPECT_THROW(ReadViewsFolder(temp / "swapped"), Error);                   // no naming it knows ('-')

  // Numbers too long to be indices are not parsed as such (no overflow, an lfsp::Error at most).
  fs::create_directories(temp / "long");
  testing::WriteBytes(temp / "long" / "99999999999999999999_1.png", "x");
  testing::WriteBytes(temp / "long" / "99999999999999999999_2.png", "x");
  EXPECT_THROW(ReadViewsFolder(temp / "long"), Error);

  // A view missing from the grid is named.
  fs::remove(temp / "epinet" / "2067_02_03.png");
  try {
    ReadViewsFolder(temp / "epinet");
    ADD_FAILURE() << "expected lfsp::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("row 2, column 3"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lfsp
