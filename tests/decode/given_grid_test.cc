// A lenslet grid the user already holds (issue 17): LFToolbox's LensletGridModel (CalInfo.json) and lfsp's own
// grid.json, read into the decoder's lattice and used by `lfsp decode --grid` / `lfsp pipeline --grid` instead of a
// fitted grid. LFToolbox's model is 1-based; reading it as 0-based would put every lens one pixel off, which the
// decode comparison below shows plainly.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/decode/given_grid.h"
#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::RunLfsp;
using testing::SourceDir;
using testing::TempDir;

nlohmann::json ReadJson(const fs::path& path) { return nlohmann::json::parse(testing::ReadBytes(path)); }

void WriteJson(const nlohmann::json& json, const fs::path& path) { testing::WriteBytes(path, json.dump(1)); }

// Where LFToolbox puts lens (c, r) (0-based column and row of its own grid), in 1-based pixel coordinates, written
// out from its documented model rather than through lfsp's lattice.
void LfToolboxCentre(const nlohmann::json& m, int c, int r, double& x, double& y) {
  const bool shifted = (r + 1 - m["FirstPosShiftRow"].get<int>()) % 2 == 0;
  const double gx = (c + (shifted ? 0.5 : 0.0)) * m["HSpacing"].get<double>();
  const double gy = r * m["VSpacing"].get<double>();
  const double a = m["Rot"].get<double>();
  x = m["HOffset"].get<double>() + std::cos(a) * gx - std::sin(a) * gy;
  y = m["VOffset"].get<double>() + std::sin(a) * gx + std::cos(a) * gy;
}

// The real F01 calibration: every usable lens of lfsp's grid is one of LFToolbox's lenses, one pixel up and left
// of where LFToolbox's 1-based coordinates put it, and the usable range is LFToolbox's grid less its partial border.
TEST(GivenGrid, RealLfToolboxCalInfoIsTheSameLattice) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path calinfo = data / "lytro_views" / "f01_lftoolbox" / "CalInfo.json";
  const nlohmann::json model = ReadJson(calinfo)["LensletGridModel"];
  const int size = 3280;  // the F01 sensor
  const decode::LensletGrid grid = decode::ReadGivenGrid(calinfo, size, size, 0.5 * (size - 1), 0.5 * (size - 1));
  EXPECT_DOUBLE_EQ(grid.spacing_x, model["HSpacing"].get<double>());
  EXPECT_DOUBLE_EQ(grid.spacing_y, model["VSpacing"].get<double>());
  EXPECT_NE(grid.fit_method.find("LFToolbox"), std::string::npos);
  // 328 x 379 lenses in LFToolbox's grid; whole micro-images on the sensor leave a lens or two fewer each way.
  EXPECT_GE(grid.columns, model["UMax"].get<int>() - 3);
  EXPECT_LE(grid.columns, model["UMax"].get<int>());
  EXPECT_GE(grid.rows, model["VMax"].get<int>() - 3);
  EXPECT_LE(grid.rows, model["VMax"].get<int>());
  double worst = 0.0;
  for (int j = 0; j < grid.rows; j += 7)
    for (int i = 0; i < grid.columns; i += 5) {
      double x = 0.0, y = 0.0;
      grid.Centre(i, j, x, y);
      // LFToolbox's lens at this place: its row and column from the (nearly unrotated) position.
      const int r = static_cast<int>(std::lround((y + 1.0 - model["VOffset"].get<double>()) / grid.spacing_y));
      double lx = 0.0, ly = 0.0;
      LfToolboxCentre(model, 0, r, lx, ly);
      const int c = static_cast<int>(std::lround((x + 1.0 - lx) / grid.spacing_x));
      LfToolboxCentre(model, c, r, lx, ly);
      worst = std::max(worst, std::hypot(x - (lx - 1.0), y - (ly - 1.0)));
    }
  EXPECT_LT(worst, 1e-9);
}

// Decoding the bundled F01 sample with its true lattice written as an LFToolbox model gives the light field the
// fitted grid gives (the fit is within 0.08 px of the truth); the same model read as if it were 0-based does not.
TEST(GivenGrid, DecodeWithAnLfToolboxModelMatchesTheFittedGrid) {
  const fs::path capture = SourceDir() / "samples" / "mini-f01" / "capture.lfp";
  ASSERT_TRUE(fs::exists(capture)) << testing::kMissingSample;
  TempDir dir;
  const nlohmann::json truth =
      ReadJson(SourceDir() / "samples" / "mini-f01" / "ground_truth" / "lenslet_geometry.json");
  nlohmann::json model = truth["lftoolbox_grid_model"];
  WriteJson({{"LensletGridModel", model}}, dir / "CalInfo.json");
  model["HOffset"] = model["HOffset"].get<double>() - 1.0;
  model["VOffset"] = model["VOffset"].get<double>() - 1.0;
  WriteJson({{"LensletGridModel", model}}, dir / "zero_based.json");

  auto decode = [&](const std::vector<std::string>& extra, const std::string& name) {
    std::vector<std::string> arguments = {"decode", capture.string(), "--out", (dir / name).string()};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const auto result = RunLfsp(arguments);
    EXPECT_EQ(result.exit_status, 0) << result.err;
    return LoadLightField(dir / name).light_field;
  };
  const LightField fitted = decode({}, "fitted.h5");
  const LightField given = decode({"--grid", (dir / "CalInfo.json").string()}, "given.h5");
  const LightField shifted = decode({"--grid", (dir / "zero_based.json").string()}, "shifted.h5");
  const nlohmann::json summary = ReadJson(dir / "given.summary.json");
  EXPECT_NE(summary["grid"]["fit_method"].get<std::string>().find("given: LFToolbox"), std::string::npos);
  ASSERT_EQ(fitted.shape(), given.shape());
  ASSERT_EQ(fitted.shape(), shifted.shape());
  auto rms = [&](const LightField& a, const LightField& b) {
    double sum = 0.0;
    for (std::size_t n = 0; n < a.size(); ++n) sum += std::pow(a.data()[n] - b.data()[n], 2);
    return std::sqrt(sum / static_cast<double>(a.size()));
  };
  const double given_rms = rms(fitted, given), shifted_rms = rms(fitted, shifted);
  std::printf("  fitted against given: RMS %.5f; against the model read 0-based: %.5f\n", given_rms, shifted_rms);
  EXPECT_LT(given_rms, 0.005);   // measured 0.0017
  EXPECT_GT(shifted_rms, 0.03);  // measured 0.058
}

// lfsp's own grid file round-trips: what `lfsp grid` writes, `lfsp decode --grid` uses as it is.
TEST(GivenGrid, LfspGridFileIsUsedAsItIs) {
  const fs::path capture = SourceDir() / "samples" / "mini-f01" / "capture.lfp";
  ASSERT_TRUE(fs::exists(capture)) << testing::kMissingSample;
  TempDir dir;
  auto result = RunLfsp({"grid", capture.string(), "--out", (dir / "grid.json").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  result = RunLfsp(
      {"decode", capture.string(), "--grid", (dir / "grid.json").string(), "--out", (dir / "decoded.h5").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const nlohmann::json written = ReadJson(dir / "grid.json")["grid"];
  const nlohmann::json used = ReadJson(dir / "decoded.summary.json")["grid"];
  for (const char* key : {"spacing_x", "spacing_y", "rotation", "origin_x", "origin_y", "columns", "rows"})
    EXPECT_EQ(used[key], written[key]) << key;
  EXPECT_NE(used["fit_method"].get<std::string>().find("given: lfsp grid"), std::string::npos);
}

// Bad grid files: one line naming the file and the problem, exit status 2, nothing written.
TEST(GivenGrid, BadGridFilesExit2AndWriteNothing) {
  const fs::path capture = SourceDir() / "samples" / "mini-f01" / "capture.lfp";
  ASSERT_TRUE(fs::exists(capture)) << testing::kMissingSample;
  TempDir dir;
  const nlohmann::json truth =
      ReadJson(SourceDir() / "samples" / "mini-f01" / "ground_truth" / "lenslet_geometry.json");
  nlohmann::json vertical = truth["lftoolbox_grid_model"];
  vertical["Orientation"] = "vert";
  WriteJson({{"LensletGridModel", vertical}}, dir / "vert.json");
  nlohmann::json no_spacing = truth["lftoolbox_grid_model"];
  no_spacing["VSpacing"] = "eight";
  WriteJson(no_spacing, dir / "no_spacing.json");
  WriteJson({{"grid",
              {{"spacing_x", 14.0},
               {"spacing_y", 12.1},
               {"rotation", 0.0},
               {"origin_x", 10.0},
               {"origin_y", 10.0},
               {"row_shift", 0},
               {"columns", 70},
               {"rows", 60},
               {"sensor_width", 7728},
               {"sensor_height", 5368}}}},
            dir / "other_sensor.json");
  testing::WriteBytes(dir / "garbage.json", "{\"HSpacing\": [");
  WriteJson({{"something", 1}}, dir / "unrelated.json");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"vert.json", "LensletGridModel.Orientation 'vert' is not supported"},
      {"no_spacing.json", "VSpacing is not a number"},
      {"other_sensor.json", "the grid is for a 7728x5368 sensor, the capture's is 1024x1024"},
      {"garbage.json", "not valid JSON"},
      {"unrelated.json", "holds no lenslet grid"},
  };
  for (const auto& [name, message] : cases) {
    const fs::path out = dir / (name + ".h5");
    const auto result = RunLfsp({"decode", capture.string(), "--grid", (dir / name).string(), "--out", out.string()});
    EXPECT_EQ(result.exit_status, 2) << name;
    EXPECT_NE(result.err.find(name), std::string::npos) << result.err;
    EXPECT_NE(result.err.find(message), std::string::npos) << result.err;
    EXPECT_FALSE(fs::exists(out)) << name;
  }
}

}  // namespace
}  // namespace lfsp
