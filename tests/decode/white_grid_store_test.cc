// The lenslet grids `lfsp whites build` stores in the white-image database (issue 46): each is the grid a decode
// would fit on that white image, it survives the JSON file exactly, a grid of another fit revision or a malformed one
// is left out, a white image changed since it was indexed has its grid fitted again, a database met under the searched
// folder spares only the white images it measured as they are now, and a decode that takes the stored grid writes the
// very views a fitting decode writes.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/decode/white_database.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ErrorOf;
using lfsp::testing::ReadBytes;
using lfsp::testing::TempDir;
using lfsp::testing::WriteBytes;

// The bundled mini-F01 sample (capture.lfp beside whites/) copied into `dir`, so that a database can be written.
void CopyMiniF01(const fs::path& dir) {
  const fs::path sample = lfsp::testing::SourceDir() / "samples" / "mini-f01";
  ASSERT_TRUE(fs::is_regular_file(sample / "capture.lfp")) << lfsp::testing::kMissingSample;
  fs::copy_file(sample / "capture.lfp", dir / "capture.lfp");
  fs::copy(sample / "whites", dir / "whites");
}

// The grid a decode fits on the white image of `entry` (capture_decoder.cc, with the white image's own metadata).
LensletGrid GridADecodeFits(const WhiteImageEntry& entry) {
  const RawImage raw = ReadWhiteImageRaw(entry);
  const LytroMetadata metadata = ReadWhiteImageMetadata(entry);
  return FitGridOnWhiteImage(WhiteImageToGrey(raw, metadata.RequireRawFormat(), metadata.source), metadata).grid;
}

const WhiteImageEntry& Named(const WhiteImageDatabase& db, const std::string& name) {
  const auto found =
      std::find_if(db.entries.begin(), db.entries.end(), [&](const WhiteImageEntry& e) { return e.name == name; });
  if (found == db.entries.end()) throw std::runtime_error("no entry " + name);
  return *found;
}

// A file's modification time moved by `seconds`, its bytes kept: to the file system, another file.
void Retouch(const fs::path& path, int seconds) {
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(seconds));
}

TEST(WhiteGridStore, EachStoredGridIsTheOneADecodeFitsAndSurvivesTheFile) {
  TempDir dir;
  CopyMiniF01(dir.path());
  WhiteImageDatabase db = BuildWhiteImageDatabase(dir / "whites");
  for (const WhiteImageEntry& e : db.entries) EXPECT_FALSE(e.grid.has_value()) << "built without fitting";
  const int fitted = FitWhiteImageGrids(db);
  int usable = 0;
  for (const WhiteImageEntry& e : db.entries) usable += e.dark ? 0 : 1;
  ASSERT_GT(usable, 0);
  EXPECT_EQ(fitted, usable);
  for (const WhiteImageEntry& e : db.entries) {
    if (e.dark) continue;
    ASSERT_TRUE(e.grid.has_value()) << e.name;
    EXPECT_EQ(e.grid->ToJson(), GridADecodeFits(e).ToJson()) << e.name;
  }
  const fs::path file = dir / "whites" / kWhiteDatabaseFileName;
  WriteWhiteImageDatabase(db, file);
  const WhiteImageDatabase back = ReadWhiteImageDatabase(file);
  ASSERT_EQ(back.entries.size(), db.entries.size());
  for (std::size_t i = 0; i < db.entries.size(); ++i) {
    ASSERT_EQ(back.entries[i].grid.has_value(), db.entries[i].grid.has_value());
    if (db.entries[i].grid) {  // every double back to the bit: the decode's views depend on them
      EXPECT_EQ(back.entries[i].grid->ToJson(), db.entries[i].grid->ToJson());
    }
  }
}

TEST(WhiteGridStore, TheFitIsPinnedSoAChangeBumpsTheRevision) {
  TempDir dir;
  CopyMiniF01(dir.path());
  const WhiteImageDatabase db = BuildWhiteImageDatabase(dir / "whites");
  const LensletGrid grid = GridADecodeFits(Named(db, "MOD_0000"));
  // Fitted at kWhiteGridFitRevision 1. If the fit now gives another grid for the same white image, grids stored by
  // earlier builds are not the ones a decode would fit: bump kWhiteGridFitRevision (white_database.h), then pin anew.
  const std::string bump = "the grid fit changed: bump kWhiteGridFitRevision in white_database.h, then update this pin";
  EXPECT_EQ(kWhiteGridFitRevision, 1) << "pin the grid the new revision fits";
  EXPECT_EQ(grid.columns, 102) << bump;
  EXPECT_EQ(grid.rows, 117) << bump;
  EXPECT_EQ(grid.row_shift, 0) << bump;
  EXPECT_NEAR(grid.spacing_x, 9.92746676203993, 1e-9) << bump;
  EXPECT_NEAR(grid.spacing_y, 8.60172873636375, 1e-9) << bump;
  EXPECT_NEAR(grid.rotation, 0.0019301082778721836, 1e-12) << bump;
  EXPECT_NEAR(grid.origin_x, 8.101530213873804, 1e-9) << bump;
  EXPECT_NEAR(grid.origin_y, 11.21914488676208, 1e-9) << bump;
}

TEST(WhiteGridStore, AnotherFitRevisionOrAMalformedGridIsLeftOut) {
  TempDir dir;
  CopyMiniF01(dir.path());
  WhiteImageDatabase db = BuildWhiteImageDatabase(dir / "whites");
  ASSERT_GT(FitWhiteImageGrids(db), 0);
  const fs::path file = dir / "whites" / kWhiteDatabaseFileName;
  WriteWhiteImageDatabase(db, file);
  const nlohmann::json written = nlohmann::json::parse(ReadBytes(file));
  ASSERT_TRUE(written["entries"][0].contains("grid"));
  const auto grids = [&](const nlohmann::json& doc) {
    WriteBytes(file, doc.dump());
    int count = 0;
    for (const WhiteImageEntry& e : ReadWhiteImageDatabase(file).entries) count += e.grid.has_value() ? 1 : 0;
    return count;
  };
  const int all = static_cast<int>(db.entries.size());
  EXPECT_EQ(grids(written), all);

  nlohmann::json doc = written;
  doc["grid_fit_revision"] = kWhiteGridFitRevision + 1;
  EXPECT_EQ(grids(doc), 0);
  doc.erase("grid_fit_revision");  // a database from before grids were stored
  EXPECT_EQ(grids(doc), 0);

  // A grid is a cache: a malformed one, one of another sensor, one whose lenses leave the sensor or one shaped so that
  // the views would be of any size is left out, and the database stays usable.
  for (const auto& [field, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"spacing_x", "wide"}, {"sensor_width", 7728}, {"columns", 100000}, {"spacing_x", 300.0}, {"rows", 2}}) {
    doc = written;
    doc["entries"][0]["grid"][field] = value;
    EXPECT_EQ(grids(doc), all - 1) << field << " " << value;
  }
}

TEST(WhiteGridStore, ADatabaseMetUnderTheFolderSparesOnlyWhatItMeasuredAsItIsNow) {
  TempDir dir;
  CopyMiniF01(dir.path());
  const WhiteImageDatabase measured = BuildWhiteImageDatabase(dir.path());  // searched as a decode searches
  WhiteImageDatabase db = BuildWhiteImageDatabase(dir / "whites");
  ASSERT_GT(FitWhiteImageGrids(db), 0);
  const fs::path file = dir / "whites" / kWhiteDatabaseFileName;
  WriteWhiteImageDatabase(db, file);
  // Every entry's mean level tampered with, so that an entry taken from whites/whites.json shows it.
  nlohmann::json doc = nlohmann::json::parse(ReadBytes(file));
  for (auto& entry : doc["entries"]) entry["mean_level"] = 0.123;
  WriteBytes(file, doc.dump());

  WhiteImageDatabase taken = LoadOrBuildWhiteImageDatabase(dir.path());
  ASSERT_EQ(taken.entries.size(), measured.entries.size());
  for (const WhiteImageEntry& e : taken.entries) {
    EXPECT_EQ(e.mean_level, 0.123) << e.name << " was measured again";
    EXPECT_TRUE(e.grid.has_value()) << e.name;
  }

  // A white image touched since (another file to the file system) is measured again and loses its grid; a removed
  // one is gone; an added one is measured.
  Retouch(dir / "whites" / "MOD_0001.RAW", 5);
  fs::remove(dir / "whites" / "MOD_0002.RAW");
  fs::remove(dir / "whites" / "MOD_0002.TXT");
  fs::create_directories(dir / "more");
  fs::copy_file(dir / "whites" / "MOD_0000.RAW", dir / "more" / "MOD_0007.RAW");
  fs::copy_file(dir / "whites" / "MOD_0000.TXT", dir / "more" / "MOD_0007.TXT");
  taken = LoadOrBuildWhiteImageDatabase(dir.path());
  ASSERT_EQ(taken.entries.size(), 3u);
  EXPECT_EQ(Named(taken, "MOD_0000").mean_level, 0.123);
  EXPECT_TRUE(Named(taken, "MOD_0000").grid.has_value());
  EXPECT_EQ(Named(taken, "MOD_0001").mean_level, Named(measured, "MOD_0001").mean_level);
  EXPECT_FALSE(Named(taken, "MOD_0001").grid.has_value());
  EXPECT_EQ(Named(taken, "MOD_0007").mean_level, Named(measured, "MOD_0000").mean_level);

  // `whites build` of the parent measures everything itself.
  for (const WhiteImageEntry& e : BuildWhiteImageDatabase(dir.path()).entries) EXPECT_NE(e.mean_level, 0.123);

  // A broken database is named in a warning and spares nothing, even beside a link that loops back.
  WriteBytes(file, "{\"lfsp_white_image_database\": 1, \"entries\": [{\"name\": 3}]}");
  fs::create_directory_symlink(".", dir / "whites" / "self");
  fs::create_directory_symlink("..", dir / "whites" / "parent");
  const WhiteImageDatabase afresh = LoadOrBuildWhiteImageDatabase(dir.path());
  ASSERT_EQ(afresh.entries.size(), 3u);
  for (const WhiteImageEntry& e : afresh.entries) {
    EXPECT_FALSE(e.grid.has_value());
    EXPECT_NE(e.mean_level, 0.123);
  }
}

// Bytes, not values: the stored grid must give the fitted grid's views exactly.
bool SameLightField(const fs::path& a, const fs::path& b) {
  const Bundle x = ReadBundle(a), y = ReadBundle(b);
  const LightField &lx = x.light_field, &ly = y.light_field;
  return lx.shape() == ly.shape() && std::memcmp(lx.data(), ly.data(), lx.size() * sizeof(*lx.data())) == 0 &&
         lx.HasWeights() == ly.HasWeights();
}

TEST(WhiteGridStore, ADecodeTakesTheStoredGridAndWritesTheSameViews) {
  TempDir dir;
  CopyMiniF01(dir.path());
  const auto decode = [&](const std::string& name) {
    const auto run = lfsp::testing::RunLfsp({"decode", (dir / "capture.lfp").string(), "--out", (dir / name).string()});
    EXPECT_EQ(run.exit_status, 0) << run.err;
    return lfsp::testing::LoadJson(dir / (fs::path(name).stem().string() + ".summary.json"))["grid_source"];
  };
  EXPECT_EQ(decode("fitted.h5"), "fitted");

  // Indexed without grids, the decode still fits; with them, it takes the stored one (from whites/whites.json,
  // though the decode looks for white images from the capture's folder).
  auto build = lfsp::testing::RunLfsp({"whites", "build", (dir / "whites").string(), "--no-grids"});
  ASSERT_EQ(build.exit_status, 0) << build.err;
  EXPECT_NE(build.out.find("0 lenslet grids fitted"), std::string::npos) << build.out;
  EXPECT_EQ(decode("indexed.h5"), "fitted");
  build = lfsp::testing::RunLfsp({"whites", "build", (dir / "whites").string()});
  ASSERT_EQ(build.exit_status, 0) << build.err;
  EXPECT_EQ(build.out.find(" 0 lenslet grids fitted"), std::string::npos) << build.out;
  EXPECT_EQ(decode("stored.h5"), "database");
  EXPECT_TRUE(SameLightField(dir / "fitted.h5", dir / "stored.h5"));
  EXPECT_TRUE(SameLightField(dir / "fitted.h5", dir / "indexed.h5"));

  // Told the folder itself, the decode reads the database directly.
  const auto direct =
      lfsp::testing::RunLfsp({"decode", (dir / "capture.lfp").string(), "--out", (dir / "direct.h5").string(),
                              "--white-images", (dir / "whites").string()});
  ASSERT_EQ(direct.exit_status, 0) << direct.err;
  EXPECT_EQ(lfsp::testing::LoadJson(dir / "direct.summary.json")["grid_source"], "database");
  EXPECT_TRUE(SameLightField(dir / "fitted.h5", dir / "direct.h5"));

  // The white image the capture takes, replaced since (same bytes, another time to the file system): its stored grid
  // is not trusted, the decode says so and fits again. A grid given by the user comes first.
  const std::string chosen = lfsp::testing::LoadJson(dir / "stored.summary.json")["white_image"]["name"];
  Retouch(dir / "whites" / (chosen + ".RAW"), -3600);  // older than the database: it still counts as fresh
  const auto changed =
      lfsp::testing::RunLfsp({"decode", (dir / "capture.lfp").string(), "--out", (dir / "changed.h5").string(),
                              "--white-images", (dir / "whites").string()});
  ASSERT_EQ(changed.exit_status, 0) << changed.err;
  EXPECT_NE(changed.out.find("changed since its white-image database was built"), std::string::npos) << changed.out;
  EXPECT_EQ(lfsp::testing::LoadJson(dir / "changed.summary.json")["grid_source"], "fitted");
  const auto given =
      lfsp::testing::RunLfsp({"decode", (dir / "capture.lfp").string(), "--out", (dir / "given.h5").string(), "--grid",
                              (dir / "fitted.summary.json").string()});
  ASSERT_EQ(given.exit_status, 0) << given.err;
  EXPECT_EQ(lfsp::testing::LoadJson(dir / "given.summary.json")["grid_source"], "given");
}

}  // namespace
}  // namespace lfsp::decode
