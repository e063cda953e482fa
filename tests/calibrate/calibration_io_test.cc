// The calibration file: exact round trip, and a replay "fuzz" of damaged files (truncations, byte flips, fields of
// the wrong type) that must only ever raise lfsp::Error naming the file, never crash or throw anything else.

#include "lfsp/calibrate/calibration_io.h"

#include <gtest/gtest.h>

#include <random>

#include "lfsp/core/error.h"
#include "test_support.h"

namespace lfsp::calibrate {
namespace {

Calibration Example() {
  Calibration c;
  c.shape = {15, 15, 625, 434, 1};
  c.model.H = IntrinsicsFromSlopes({0, 9.001e-4, 1.2003e-3, -3.6e-3, 0, 9.04e-4, 1.207e-3, -3.61e-3}, c.shape);
  c.model.distortion = {0.081, -0.05, 0.001, 1.4e-3, -0.9e-3};
  c.corners_x = 19;
  c.corners_y = 19;
  c.square_size = 3.61e-3;
  c.zoom_step = 600;
  c.focus_step = 430;
  c.rms_mm = 0.0172;
  CapturePose pose;
  pose.name = "a.h5";
  pose.rotation = {0.1, 0.2, 0.3};
  pose.translation = {0.01, -0.02, 0.25};
  pose.views = {{7, 7}, {8, 7}};
  c.captures.push_back(pose);
  return c;
}

TEST(CalibrationIo, RoundTripsExactly) {
  lfsp::testing::TempDir dir;
  const Calibration c = Example();
  WriteCalibration(c, dir / "cal.json");
  const Calibration back = ReadCalibration(dir / "cal.json");
  EXPECT_EQ(back.shape, c.shape);
  for (int r = 0; r < 5; ++r)
    for (int col = 0; col < 5; ++col) EXPECT_EQ(back.model.H(r, col), c.model.H(r, col));
  EXPECT_EQ(back.model.distortion.ToArray(), c.model.distortion.ToArray());
  EXPECT_EQ(back.corners_x, 19);
  EXPECT_EQ(back.square_size, 3.61e-3);
  EXPECT_EQ(back.rms_mm, 0.0172);
}

TEST(CalibrationIo, DamagedFilesRaiseOnlyLfspErrors) {
  lfsp::testing::TempDir dir;
  const std::string good = CalibrationToJson(Example()).dump(1);
  std::mt19937 rng(5);
  int rejected = 0;
  for (int n = 0; n < 400; ++n) {
    std::string text = good;
    switch (n % 4) {
      case 0:  // truncation
        text.resize(rng() % text.size());
        break;
      case 1:  // byte flips
        for (int k = 0; k < 3; ++k) text[rng() % text.size()] = static_cast<char>(rng() % 256);
        break;
      case 2: {  // a number becomes a string
        const std::size_t at = text.find_first_of("0123456789", rng() % text.size());
        if (at != std::string::npos) text.insert(at, "\"x\",");
        break;
      }
      default: {  // a key is renamed
        const std::size_t at = text.find('"', rng() % text.size());
        if (at != std::string::npos && at + 1 < text.size()) text[at + 1] = '_';
        break;
      }
    }
    const auto path = dir / ("case" + std::to_string(n) + ".json");
    lfsp::testing::WriteBytes(path, text);
    try {
      ReadCalibration(path);
    } catch (const Error& e) {
      ++rejected;
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << n << " threw a non-lfsp exception: " << e.what();
    }
  }
  EXPECT_GT(rejected, 150);  // most damage is detected (some edits leave a valid file, e.g. inside a name)
}

TEST(CalibrationIo, MissingFileAndNonCalibrationJson) {
  lfsp::testing::TempDir dir;
  EXPECT_THROW(ReadCalibration(dir / "absent.json"), Error);
  lfsp::testing::WriteBytes(dir / "other.json", "{\"format\": \"something-else\"}");
  try {
    ReadCalibration(dir / "other.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not an lfsp calibration file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lfsp::calibrate
