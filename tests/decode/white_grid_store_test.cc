// The lenslet grids `lfsp whites build` stores in the white-image database (issue 46): each is the grid a decode
// would fit on that white image, it survives the JSON file exactly, a grid of another fit revision is ignored, a bad
// one is a clear error, and a decode that takes the stored grid writes the very views a fitting decode writes.

#include <gtest/gtest.h>

#include <cstring>

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
  const cv::Mat grey = WhiteImageToGrey(raw, metadata.RequireRawFormat(), metadata.source);
  return EstimateLensletGrid(grey, GuessFromMetadata(metadata, raw.width, raw.height)).grid;
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

TEST(WhiteGridStore, AnotherFitRevisionIsIgnoredAndABadGridIsAnError) {
  TempDir dir;
  CopyMiniF01(dir.path());
  WhiteImageDatabase db = BuildWhiteImageDatabase(dir / "whites");
  ASSERT_GT(FitWhiteImageGrids(db), 0);
  const fs::path file = dir / "whites" / kWhiteDatabaseFileName;
  WriteWhiteImageDatabase(db, file);
  const nlohmann::json written = nlohmann::json::parse(ReadBytes(file));
  ASSERT_TRUE(written["entries"][0].contains("grid"));

  nlohmann::json doc = written;
  doc["grid_fit_revision"] = kWhiteGridFitRevision + 1;
  WriteBytes(file, doc.dump());
  for (const WhiteImageEntry& e : ReadWhiteImageDatabase(file).entries) EXPECT_FALSE(e.grid.has_value()) << e.name;
  doc.erase("grid_fit_revision");  // a database from before grids were stored
  WriteBytes(file, doc.dump());
  for (const WhiteImageEntry& e : ReadWhiteImageDatabase(file).entries) EXPECT_FALSE(e.grid.has_value()) << e.name;

  doc = written;
  doc["entries"][0]["grid"]["spacing_x"] = "wide";
  WriteBytes(file, doc.dump());
  EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(file); }).find("whites.json entry 0 grid"), std::string::npos);
  doc = written;
  doc["entries"][0]["grid"]["sensor_width"] = 7728;
  WriteBytes(file, doc.dump());
  EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(file); }).find("the grid is for a 7728x"), std::string::npos);
  doc = written;
  doc["entries"][0]["grid"]["columns"] = 100000;  // a lens range beyond the sensor: slicing would read outside it
  WriteBytes(file, doc.dump());
  EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(file); }).find("micro-image off the sensor"), std::string::npos);
}

TEST(WhiteGridStore, AnIndexedSubFolderIsTakenWholeAndABrokenOneIndexedAfresh) {
  TempDir dir;
  CopyMiniF01(dir.path());
  const WhiteImageDatabase measured = BuildWhiteImageDatabase(dir.path());  // searched as a decode searches
  WhiteImageDatabase db = BuildWhiteImageDatabase(dir / "whites");
  ASSERT_GT(FitWhiteImageGrids(db), 0);
  const fs::path file = dir / "whites" / kWhiteDatabaseFileName;
  WriteWhiteImageDatabase(db, file);

  // Taken from whites/whites.json: the grids come along, and so does a (tampered) mean level, which shows that the
  // white images were not measured again.
  nlohmann::json doc = nlohmann::json::parse(ReadBytes(file));
  doc["entries"][0]["mean_level"] = 0.123;
  WriteBytes(file, doc.dump());
  const WhiteImageDatabase taken = LoadOrBuildWhiteImageDatabase(dir.path());
  ASSERT_EQ(taken.entries.size(), measured.entries.size());
  bool tampered = false;
  for (const WhiteImageEntry& e : taken.entries) {
    EXPECT_EQ(e.grid.has_value(), !e.dark) << e.name;
    tampered = tampered || e.mean_level == 0.123;
  }
  EXPECT_TRUE(tampered);

  // A broken one: the folder is indexed afresh, as if it had none.
  WriteBytes(file, "{\"lfsp_white_image_database\": 1, \"entries\": [{\"name\": 3}]}");
  const WhiteImageDatabase afresh = LoadOrBuildWhiteImageDatabase(dir.path());
  ASSERT_EQ(afresh.entries.size(), measured.entries.size());
  for (std::size_t i = 0; i < afresh.entries.size(); ++i) {
    EXPECT_FALSE(afresh.entries[i].grid.has_value());
    EXPECT_EQ(afresh.entries[i].mean_level, measured.entries[i].mean_level);
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
  EXPECT_EQ(decode("fitted.h5"), "fitted on the white image");

  // Indexed without grids, the decode still fits; with them, it takes the stored one (from whites/whites.json,
  // though the decode looks for white images from the capture's folder).
  auto build = lfsp::testing::RunLfsp({"whites", "build", (dir / "whites").string(), "--no-grids"});
  ASSERT_EQ(build.exit_status, 0) << build.err;
  EXPECT_NE(build.out.find("0 lenslet grids fitted"), std::string::npos) << build.out;
  EXPECT_EQ(decode("indexed.h5"), "fitted on the white image");
  build = lfsp::testing::RunLfsp({"whites", "build", (dir / "whites").string()});
  ASSERT_EQ(build.exit_status, 0) << build.err;
  EXPECT_EQ(build.out.find(" 0 lenslet grids fitted"), std::string::npos) << build.out;
  EXPECT_EQ(decode("stored.h5"), "the white-image database (fitted on the white image by lfsp whites build)");
  EXPECT_TRUE(SameLightField(dir / "fitted.h5", dir / "stored.h5"));
  EXPECT_TRUE(SameLightField(dir / "fitted.h5", dir / "indexed.h5"));

  // Told the folder itself, the decode reads the database directly.
  const auto direct =
      lfsp::testing::RunLfsp({"decode", (dir / "capture.lfp").string(), "--out", (dir / "direct.h5").string(),
                              "--white-images", (dir / "whites").string()});
  ASSERT_EQ(direct.exit_status, 0) << direct.err;
  EXPECT_EQ(lfsp::testing::LoadJson(dir / "direct.summary.json")["grid_source"],
            "the white-image database (fitted on the white image by lfsp whites build)");
  EXPECT_TRUE(SameLightField(dir / "fitted.h5", dir / "direct.h5"));
}

}  // namespace
}  // namespace lfsp::decode
