// The white-image database: indexing MOD_*.RAW + .TXT pairs and multi-volume calibration archives made from the real
// Illum white-image metadata, dark-frame detection, the JSON cache, and selection by serial -> nearest zoom ->
// nearest focus -> longest exposure with its explanation.

#include "lfsp/decode/white_database.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <thread>

#include "lfsp/core/error.h"
#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/lytro_capture.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ErrorOf;
using lfsp::testing::ReadBytes;
using lfsp::testing::TempDir;
using lfsp::testing::WriteBytes;

constexpr int kWidth = 16;
constexpr int kHeight = 8;

struct White {
  std::string name;
  std::string serial;
  int zoom;
  int focus;
  double exposure;
  std::uint16_t level;  // raw value of every pixel (10-bit; black 64, white 1023)
};

// The real MOD TXT with the fields of `w` (and a small sensor), as text, plus its packed raw image.
std::pair<std::string, std::vector<std::uint8_t>> MakeWhite(const fs::path& real_txt, const White& w) {
  const std::string text = ReadBytes(real_txt);
  nlohmann::json doc = nlohmann::json::parse(text);
  auto& frame = doc["master"]["picture"]["frameArray"][0]["frame"];
  frame["privateMetadata"]["camera"]["serialNumber"] = w.serial;
  frame["metadata"]["devices"]["lens"]["zoomStep"] = w.zoom;
  frame["metadata"]["devices"]["lens"]["focusStep"] = w.focus;
  frame["metadata"]["devices"]["shutter"]["frameExposureDuration"] = w.exposure;
  frame["metadata"]["image"]["width"] = kWidth;
  frame["metadata"]["image"]["height"] = kHeight;
  std::vector<std::uint16_t> pixels(kWidth * kHeight, w.level);
  pixels[5] = 1023;  // not quite flat, so the unpacked image is checked pixel by pixel below
  return {doc.dump(1, '\t'), PackRaw(RawPacking::kBits10Illum, pixels, "t")};
}

void WritePair(const fs::path& dir, const fs::path& real_txt, const White& w) {
  const auto [text, raw] = MakeWhite(real_txt, w);
  fs::create_directories(dir);
  WriteBytes(dir / (w.name + ".TXT"), text + std::string("\0\0", 2));
  WriteBytes(dir / (w.name + ".RAW"), std::string(raw.begin(), raw.end()));
}

LytroMetadata Capture(const std::string& serial, int zoom, int focus) {
  nlohmann::json md = {{"devices", {{"lens", {{"zoomStep", zoom}, {"focusStep", focus}}}}}};
  return ParseFrameMetadata(md, {{"camera", {{"serialNumber", serial}}}}, "IMG_0001.LFR");
}

class WhiteDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto data = lfsp::testing::SharedDataDir();
    if (!data) GTEST_SKIP() << "../shared/data not found: white-image tests need the real MOD TXT";
    real_txt_ = *data / "lytro" / "illum_whiteimage_metadata.TXT";
    const fs::path cam = dir_.path() / "Cameras" / "B5000000001";
    for (const White& w : {White{"MOD_0000", "B5000000001", 100, 800, 0.007, 900},
                           White{"MOD_0001", "B5000000001", 120, 700, 0.007, 900},
                           White{"MOD_0002", "B5000000001", 120, 820, 0.007, 900},
                           White{"MOD_0003", "B5000000001", 120, 820, 0.014, 950},
                           White{"MOD_0004", "B5000000001", 120, 814, 0.02, 70},  // dark: mean ~0.006
                           White{"MOD_0005", "B5000000001", 130, 814, 0.007, 900}}) {
      WritePair(cam, real_txt_, w);
    }
    WritePair(dir_.path() / "Cameras" / "B5000000002", real_txt_, {"MOD_0000", "B5000000002", 123, 814, 0.007, 900});
    WriteBytes(cam / "MOD_0099.TXT", ReadBytes(real_txt_));  // no RAW beside it
    WritePair(cam, real_txt_, {"MOD_0098", "B5000000001", 1, 1, 0.007, 900});
    WriteBytes(cam / "MOD_0098.RAW", "short");  // wrong size
  }

  TempDir dir_;
  fs::path real_txt_;
};

TEST_F(WhiteDatabaseTest, IndexesPairsAndSaysWhatItSkipped) {
  const WhiteImageDatabase db = BuildWhiteImageDatabase(dir_.path());
  ASSERT_EQ(db.entries.size(), 7u);
  ASSERT_EQ(db.skipped.size(), 2u);
  EXPECT_NE(db.skipped[0].find("MOD_0098.RAW: raw buffer of 5 bytes, expected 160 bytes"), std::string::npos)
      << db.skipped[0];
  EXPECT_NE(db.skipped[1].find("MOD_0099.TXT: no .RAW beside it"), std::string::npos) << db.skipped[1];
  const WhiteImageEntry& first = db.entries.front();  // sorted by serial, zoom, focus
  EXPECT_EQ(first.name, "MOD_0000");
  EXPECT_EQ(first.serial, "B5000000001");
  EXPECT_EQ(first.camera_model, "B01");
  EXPECT_EQ(first.zoom_step, 100);
  EXPECT_EQ(first.focus_step, 800);
  EXPECT_DOUBLE_EQ(first.exposure_duration, 0.007);
  EXPECT_EQ(first.width, kWidth);
  EXPECT_EQ(first.packing, RawPacking::kBits10Illum);
  // Mean level: (127 * 900 + 1023) / 128 px, black 64, white 1023.
  EXPECT_NEAR(first.mean_level, ((127.0 * 900 + 1023) / 128 - 64) / (1023 - 64), 1e-12);
  EXPECT_FALSE(first.dark);
  int dark = 0;
  for (const auto& e : db.entries) dark += e.dark ? 1 : 0;
  EXPECT_EQ(dark, 1);
  const RawImage raw = ReadWhiteImageRaw(first);
  EXPECT_EQ(raw.at(0, 5), 1023);
  EXPECT_EQ(raw.at(7, 15), 900);
  EXPECT_EQ(ReadWhiteImageMetadata(first).serial, "B5000000001");
}

TEST_F(WhiteDatabaseTest, SelectsBySerialThenNearestZoomThenFocusThenExposure) {
  const WhiteImageDatabase db = BuildWhiteImageDatabase(dir_.path());
  // Zoom 123: 120 (off 3) beats 130 (off 7); at zoom 120, focus 814 is MOD_0004 but that is dark, so 820 (off 6)
  // wins over 700; of the two at 820 the longer exposure (MOD_0003) is chosen. The other camera's exact match is
  // not considered.
  const WhiteImageChoice choice = SelectWhiteImage(db, Capture("B5000000001", 123, 814));
  ASSERT_NE(choice.entry, nullptr);
  EXPECT_EQ(choice.entry->name, "MOD_0003");
  EXPECT_EQ(choice.entry->serial, "B5000000001");
  EXPECT_NE(choice.explanation.find("camera serial B5000000001 (5 of 6 usable white images)"), std::string::npos)
      << choice.explanation;
  EXPECT_NE(choice.explanation.find("zoom step 120 nearest to the capture's 123 (off by 3)"), std::string::npos)
      << choice.explanation;
  EXPECT_NE(choice.explanation.find("focus step 820 nearest to 814"), std::string::npos) << choice.explanation;
  EXPECT_NE(choice.explanation.find("longest exposure (0.014 s) of 2"), std::string::npos) << choice.explanation;

  EXPECT_EQ(SelectWhiteImage(db, Capture("B5000000002", 0, 0)).entry->serial, "B5000000002");
  EXPECT_EQ(SelectWhiteImage(db, Capture("B5000000001", 140, 0)).entry->name, "MOD_0005");
  EXPECT_EQ(SelectWhiteImage(db, Capture("B5000000001", 90, 900)).entry->name, "MOD_0000");
}

TEST_F(WhiteDatabaseTest, NoWhiteImageForTheSerialIsAClearError) {
  const WhiteImageDatabase db = BuildWhiteImageDatabase(dir_.path());
  const std::string message = ErrorOf([&] { SelectWhiteImage(db, Capture("B5999", 123, 814)); });
  EXPECT_NE(message.find("IMG_0001.LFR: no white image for camera serial B5999"), std::string::npos) << message;
  EXPECT_NE(message.find("B5000000001, B5000000002"), std::string::npos) << message;
  nlohmann::json md = {{"devices", {{"lens", {{"focusStep", 3}}}}}};
  EXPECT_NE(ErrorOf([&] { SelectWhiteImage(db, ParseFrameMetadata(md, {}, "c")); }).find("zoomStep is missing"),
            std::string::npos);
}

TEST_F(WhiteDatabaseTest, JsonCacheRoundTripAndFreshness) {
  const WhiteImageDatabase db = BuildWhiteImageDatabase(dir_.path());
  const fs::path cache = dir_.path() / kWhiteDatabaseFileName;
  WriteWhiteImageDatabase(db, cache);
  const WhiteImageDatabase back = ReadWhiteImageDatabase(cache);
  ASSERT_EQ(back.entries.size(), db.entries.size());
  for (std::size_t i = 0; i < db.entries.size(); ++i) {
    EXPECT_EQ(back.entries[i].name, db.entries[i].name);
    EXPECT_EQ(fs::canonical(back.entries[i].raw_path), fs::canonical(db.entries[i].raw_path));
    EXPECT_EQ(back.entries[i].zoom_step, db.entries[i].zoom_step);
    EXPECT_EQ(back.entries[i].exposure_duration, db.entries[i].exposure_duration);
    EXPECT_EQ(back.entries[i].dark, db.entries[i].dark);
    EXPECT_DOUBLE_EQ(back.entries[i].mean_level, db.entries[i].mean_level);
  }
  EXPECT_EQ(back.skipped, db.skipped);
  EXPECT_EQ(ReadWhiteImageRaw(back.entries[0]).pixels, ReadWhiteImageRaw(db.entries[0]).pixels);

  // A fresh cache is used as is (tamper with it to see that), a newer MOD file makes it stale.
  nlohmann::json tampered = nlohmann::json::parse(ReadBytes(cache));
  tampered["entries"][0]["zoom_step"] = 4242;
  WriteBytes(cache, tampered.dump());
  const auto has_tampered = [](const WhiteImageDatabase& d) {
    return std::any_of(d.entries.begin(), d.entries.end(), [](const auto& e) { return e.zoom_step == 4242; });
  };
  EXPECT_TRUE(has_tampered(LoadOrBuildWhiteImageDatabase(dir_.path())));
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const fs::path touched = dir_.path() / "Cameras" / "B5000000001" / "MOD_0000.RAW";
  fs::last_write_time(touched, fs::file_time_type::clock::now() + std::chrono::seconds(5));
  EXPECT_FALSE(has_tampered(LoadOrBuildWhiteImageDatabase(dir_.path())));
}

TEST_F(WhiteDatabaseTest, BadCacheFiles) {
  const fs::path cache = dir_.path() / "bad.json";
  WriteBytes(cache, "{\"entries\": []}");
  EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(cache); }).find("not an lfsp white-image database"),
            std::string::npos);
  WriteBytes(cache, R"({"lfsp_white_image_database": 1, "entries": [{"name": "MOD_0000"}]})");
  EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(cache); }).find("bad.json entry 0: metadata field raw is missing"),
            std::string::npos);
  // Found by make fuzz: a size beyond int's range was converted to int (undefined behaviour).
  for (const char* height : {"7909551257841861", "1.5", "-1e300"}) {
    WriteBytes(cache, std::string(R"({"lfsp_white_image_database": 1, "entries": [{"name": "M", "raw": "M.RAW",
        "metadata": "M.TXT", "serial": "s", "zoom_step": 1, "focus_step": 2, "exposure_s": 0.1, "width": 8,
        "height": )") + height +
                          R"(, "bits_per_pixel": 10}]})");
    EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(cache); }).find("height is not a whole number"), std::string::npos)
        << height;
  }
  TempDir empty;
  EXPECT_NE(ErrorOf([&] { BuildWhiteImageDatabase(empty.path()); }).find("no white image found"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { BuildWhiteImageDatabase(empty / "missing"); }).find("not a folder"), std::string::npos);
}

TEST(WhiteDatabaseArchive, MultiVolumeCalibrationArchive) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const auto [text, raw] =
      MakeWhite(data / "lytro" / "illum_whiteimage_metadata.TXT", {"MOD_0007", "B5123", 7, 9, 0.01, 800});
  // Volume 0 holds the TXT, volume 1 the RAW (LFToolbox: data.C.0 ... data.C.N, files[] and nextFile).
  LfpContainer volume0;
  const std::string txt_ref = volume0.AddBinary(std::vector<std::uint8_t>(text.begin(), text.end()));
  volume0.AddJson(
      {{"files", {{{"name", "C:\\T1CALIB\\MOD_0007.TXT"}, {"dataRef", txt_ref}}}}, {"nextFile", "data.C.1"}},
      SectionKind::kMetadata);
  LfpContainer volume1;
  const std::string raw_ref = volume1.AddBinary(raw);
  volume1.AddJson({{"files", {{{"name", "C:\\T1CALIB\\MOD_0007.RAW"}, {"dataRef", raw_ref}}}}}, SectionKind::kMetadata);
  TempDir dir;
  WriteLfpContainer(volume0, dir / "data.C.0");
  WriteLfpContainer(volume1, dir / "data.C.1");
  const WhiteImageDatabase db = BuildWhiteImageDatabase(dir.path());
  ASSERT_EQ(db.entries.size(), 1u) << (db.skipped.empty() ? "" : db.skipped[0]);
  const WhiteImageEntry& e = db.entries[0];
  EXPECT_EQ(e.name, "MOD_0007");
  EXPECT_EQ(e.serial, "B5123");
  EXPECT_EQ(e.raw_member, "C:\\T1CALIB\\MOD_0007.RAW");
  EXPECT_EQ(e.raw_path.filename(), "data.C.1");
  EXPECT_EQ(e.metadata_path.filename(), "data.C.0");
  EXPECT_EQ(ReadWhiteImageRaw(e).at(3, 3), 800);
  EXPECT_EQ(ReadWhiteImageMetadata(e).zoom_step, 7);
  WriteWhiteImageDatabase(db, dir / kWhiteDatabaseFileName);
  EXPECT_EQ(ReadWhiteImageDatabase(dir / kWhiteDatabaseFileName).entries[0].raw_member, e.raw_member);
}

// A whites.json with the marker but no entries is not a database (fuzz finding, decode/fuzz_white_folder: the const
// document's [] of the missing key read past a freed or foreign block under ASan).
TEST(WhiteDatabaseCache, MarkerWithoutEntriesIsRefused) {
  TempDir temp;
  for (const char* text : {R"({"lfsp_white_image_database": 1})", R"({"lfsp_white_image_database": 1, "x": []})"}) {
    WriteBytes(temp / "whites.json", text);
    EXPECT_NE(ErrorOf([&] { ReadWhiteImageDatabase(temp / "whites.json"); }).find("not an lfsp white-image database"),
              std::string::npos)
        << text;
  }
}

// A white-image TXT with only the fields the database reads (4x2, 12-bit), and its raw image.
void WriteSmallPair(const fs::path& txt) {
  const nlohmann::json metadata = {
      {"image",
       {{"width", 4},
        {"height", 2},
        {"rawDetails",
         {{"pixelPacking", {{"endianness", "big"}, {"bitsPerPixel", 12}}},
          {"pixelFormat",
           {{"black", {{"r", 64}, {"gr", 64}, {"gb", 64}, {"b", 64}}},
            {"white", {{"r", 4095}, {"gr", 4095}, {"gb", 4095}, {"b", 4095}}}}},
          {"mosaic", {{"tile", "r,gr:gb,b"}, {"upperLeftPixel", "gr"}}}}}}},
      {"devices", {{"lens", {{"zoomStep", 100}, {"focusStep", 800}}}, {"shutter", {{"frameExposureDuration", 0.01}}}}}};
  const nlohmann::json doc = {
      {"master",
       {{"picture",
         {{"frameArray",
           {{{"frame", {{"metadata", metadata}, {"privateMetadata", {{"camera", {{"serialNumber", "A1"}}}}}}}}}}}}}}};
  fs::create_directories(txt.parent_path());
  WriteBytes(txt, doc.dump());
  const std::vector<std::uint8_t> raw = PackRaw(RawPacking::kBits12BigEndian, std::vector<std::uint16_t>(8, 3000), "t");
  fs::path raw_path = txt;
  WriteBytes(raw_path.replace_extension(".RAW"), std::string(raw.begin(), raw.end()));
}

// whites.json holds names as UTF-8 text: a white image whose file name is not UTF-8 is skipped with a reason (fuzz
// finding, decode/fuzz_white_folder: such a name in a skip reason made `lfsp whites build` an internal failure), and
// a folder whose own name is not UTF-8 still gives a database that can be written.
TEST(WhiteDatabaseNames, FileNamesThatAreNotUtf8AreSkipped) {
  TempDir temp;
  const fs::path dir = temp / "whites";
  WriteSmallPair(dir / "MOD_0000.TXT");
  WriteSmallPair(dir / "MOD_\xfa.TXT");
  fs::create_directories(dir / "sub\xff");
  WriteBytes(dir / "sub\xff" / "MOD_0001.TXT", "{}");  // no .RAW beside it: its reason quotes the name
  WhiteImageDatabase db = BuildWhiteImageDatabase(dir);
  ASSERT_EQ(db.entries.size(), 1u);
  EXPECT_EQ(db.entries[0].name, "MOD_0000");
  ASSERT_EQ(db.skipped.size(), 2u);
  for (const std::string& reason : db.skipped) EXPECT_NE(reason.find("\\x"), std::string::npos) << reason;
  EXPECT_EQ(std::count_if(db.skipped.begin(), db.skipped.end(),
                          [](const std::string& reason) { return reason.find("is not UTF-8") != std::string::npos; }),
            1);
  EXPECT_NO_THROW(WriteWhiteImageDatabase(db, dir / kWhiteDatabaseFileName));
  EXPECT_EQ(ReadWhiteImageDatabase(dir / kWhiteDatabaseFileName).entries.size(), 1u);

  const fs::path odd = temp / "whites_\xfa";
  WriteSmallPair(odd / "MOD_0000.TXT");
  WriteBytes(odd / "MOD_0002.TXT", "{}");  // no .RAW beside it: its reason quotes the folder's name
  db = BuildWhiteImageDatabase(odd);
  ASSERT_EQ(db.skipped.size(), 1u);
  EXPECT_NE(db.skipped[0].find("whites_\\xFA"), std::string::npos) << db.skipped[0];
  EXPECT_NO_THROW(WriteWhiteImageDatabase(db, odd / kWhiteDatabaseFileName));

  const auto build = lfsp::testing::RunLfsp({"whites", "build", dir.string()});
  EXPECT_EQ(build.exit_status, 0) << build.err;
}

}  // namespace
}  // namespace lfsp::decode

namespace lfsp::decode {
namespace {

TEST_F(WhiteDatabaseTest, CliBuildAndSelect) {
  const auto build = lfsp::testing::RunLfsp({"whites", "build", dir_.path().string()});
  ASSERT_EQ(build.exit_status, 0) << build.err;
  EXPECT_NE(build.out.find("7 white images indexed"), std::string::npos) << build.out;
  EXPECT_EQ(ReadWhiteImageDatabase(dir_ / kWhiteDatabaseFileName).entries.size(), 7u);
  EXPECT_TRUE(fs::exists(dir_ / "whites.summary.json"));

  // A capture of camera B5000000001 at zoom 123 / focus 814, as an Illum container with inline metadata.
  LfpContainer capture;
  capture.AddJson({{"frames",
                    {{{"frame",
                       {{"metadata", {{"devices", {{"lens", {{"zoomStep", 123}, {"focusStep", 814}}}}}}},
                        {"privateMetadata", {{"camera", {{"serialNumber", "B5000000001"}}}}}}}}}}},
                  SectionKind::kMetadata);
  TempDir other;
  WriteLfpContainer(capture, other / "IMG_0001.LFR");
  const auto select =
      lfsp::testing::RunLfsp({"whites", "select", dir_.path().string(), (other / "IMG_0001.LFR").string()});
  ASSERT_EQ(select.exit_status, 0) << select.err;
  EXPECT_NE(select.out.find("MOD_0003.RAW"), std::string::npos) << select.out;
  EXPECT_NE(select.out.find("zoom step 120 nearest"), std::string::npos) << select.out;

  LfpContainer stranger;
  stranger.AddJson({{"frames",
                     {{{"frame",
                        {{"metadata", {{"devices", {{"lens", {{"zoomStep", 1}, {"focusStep", 2}}}}}}},
                         {"privateMetadata", {{"camera", {{"serialNumber", "X1"}}}}}}}}}}},
                   SectionKind::kMetadata);
  WriteLfpContainer(stranger, other / "IMG_0002.LFR");
  const auto none =
      lfsp::testing::RunLfsp({"whites", "select", dir_.path().string(), (other / "IMG_0002.LFR").string()});
  EXPECT_EQ(none.exit_status, 2);
  EXPECT_NE(none.err.find("no white image for camera serial X1"), std::string::npos) << none.err;
  EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1);

  const auto empty = lfsp::testing::RunLfsp({"whites", "build", (other / "nothing").string()});
  EXPECT_EQ(empty.exit_status, 2);
  EXPECT_FALSE(fs::exists(other / "nothing" / kWhiteDatabaseFileName));
}

}  // namespace
}  // namespace lfsp::decode
