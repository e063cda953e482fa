// `lfsp info` for Lytro files: the library description of the four real containers, extraction (JPEG, PFM depth,
// metadata JSON, archived names kept inside the folder), and the CLI on real and corrupt files.

#include "lfsp/decode/container_info.h"

#include <gtest/gtest.h>

#include <cstring>

#include "lfsp/core/error.h"
#include "lfsp/core/pfm.h"
#include "lfsp/decode/lytro_capture.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

using lfsp::testing::ReadBytes;
using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;
using lfsp::testing::WriteBytes;

struct Expected {
  const char* name;
  std::size_t sections;
  const char* model;
  int zoom;  // -1: not in the file
  int focus;
  const char* summary_part;
};

constexpr Expected kReal[] = {
    {"IMG_0001-stk.lfp", 14, "F01", -1, -1, "12 focus-stack frames 1080x1080"},
    {"IMG_0002-dm.lfp", 3, "F01", -1, -1, "1 depth map 330x330"},
    {"IMG_0002-stk.lfp", 4, "F01", -1, -1, "2 image blocks"},
    {"illum_demo.LFP", 12, "ILLUM", 123, 814, "1 depth map 88x60, 10 focus-stack frames 704x480"},
};

std::size_t Lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(ContainerInfoReal, DescribesTheFourRealContainers) {
  LFSP_REQUIRE_SHARED_DATA(data);
  for (const Expected& e : kReal) {
    SCOPED_TRACE(e.name);
    const auto path = data / "lytro" / e.name;
    EXPECT_TRUE(LooksLikeLytroFile(path));
    const nlohmann::ordered_json d = DescribeLytroFile(path);
    EXPECT_EQ(d["section_counts"]["total"], e.sections);
    EXPECT_EQ(d["section_counts"]["LFM"], 1);
    ASSERT_EQ(d["sections"].size(), e.sections);
    const std::string model = d.contains("metadata") ? d["metadata"]["camera"]["model"].get<std::string>()
                                                     : d["camera_inferred"]["model"].get<std::string>();
    EXPECT_EQ(model, e.model);
    if (e.zoom >= 0) {
      EXPECT_EQ(d["metadata"]["lens"]["zoom_step"], e.zoom);
      EXPECT_EQ(d["metadata"]["lens"]["focus_step"], e.focus);
    } else {
      EXPECT_FALSE(d.contains("metadata"));  // the F01 exports do not carry the frame metadata
    }
    EXPECT_FALSE(d["holds"]["raw_image"].get<bool>());
    EXPECT_NE(d["holds"]["summary"].get<std::string>().find(e.summary_part), std::string::npos)
        << d["holds"]["summary"];
    const std::string text = FormatLytroDescription(d);
    EXPECT_NE(text.find("every SHA-1 verified"), std::string::npos);
  }
}

TEST(ContainerInfoReal, ExtractIllumExport) {
  LFSP_REQUIRE_SHARED_DATA(data);
  TempDir dir;
  const auto source = data / "lytro" / "illum_demo.LFP";
  const auto written = ExtractLytroFile(source, dir / "out");
  std::size_t jpegs = 0;
  for (const auto& path : written) {
    if (path.extension() == ".jpg") {
      ++jpegs;
      const std::string bytes = ReadBytes(path);
      ASSERT_GE(bytes.size(), 3u);
      EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0xFF);
      EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0xD8);
    }
  }
  EXPECT_EQ(jpegs, 10u);
  // The depth map comes back from the PFM with the same values, the right way up.
  const DisparityMap depth = ReadPfm(dir / "out" / "depth_map_00.pfm");
  ASSERT_EQ(depth.width(), 88);
  ASSERT_EQ(depth.height(), 60);
  const LytroCapture capture = OpenLytroCapture(source);
  const auto& payload =
      capture.container.sections[static_cast<std::size_t>(capture.ItemsOf(ItemKind::kDepthMap)[0]->section)].payload;
  float first = 0, last_row_first = 0;
  std::memcpy(&first, payload.data(), 4);
  std::memcpy(&last_row_first, payload.data() + 4 * 88 * 59, 4);
  EXPECT_EQ(depth.at(0, 0), first);
  EXPECT_EQ(depth.at(59, 0), last_row_first);
  const nlohmann::json metadata = nlohmann::json::parse(ReadBytes(dir / "out" / "frame_metadata.json"));
  EXPECT_EQ(metadata["camera"]["model"], "ILLUM");
  const nlohmann::json manifest = nlohmann::json::parse(ReadBytes(dir / "out" / "manifest.json"));
  EXPECT_EQ(manifest["files"].size() + 1, written.size());
}

TEST(ContainerInfo, ExtractArchiveKeepsNamesInsideTheFolder) {
  LfpContainer c;
  const std::string a = c.AddBinary({1, 2, 3});
  const std::string b = c.AddBinary({4, 5});
  c.AddJson(
      {{"files",
        {{{"name", "C:\\T1CALIB\\MOD_0000.RAW"}, {"dataRef", a}}, {{"name", "..\\..\\..\\evil"}, {"dataRef", b}}}}},
      SectionKind::kMetadata);
  TempDir dir;
  WriteLfpContainer(c, dir / "data.C.0");
  ASSERT_TRUE(LooksLikeLytroFile(dir / "data.C.0"));
  ExtractLytroFile(dir / "data.C.0", dir / "x");
  EXPECT_EQ(ReadBytes(dir / "x" / "T1CALIB__MOD_0000.RAW"), std::string("\x01\x02\x03", 3));
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path())) {
    const std::string p = entry.path().lexically_relative(dir.path()).string();
    EXPECT_TRUE(p.rfind("x", 0) == 0 || p == "data.C.0") << p;
  }
}

TEST(ContainerInfo, CorruptFileWritesNothing) {
  LfpContainer c;
  c.AddJson({{"frames", nlohmann::json::array()}}, SectionKind::kMetadata);
  auto bytes = SerializeLfpContainer(c);
  bytes[16 + 96 + 3] ^= 0x20;
  TempDir dir;
  WriteBytes(dir / "bad.lfp", std::string(bytes.begin(), bytes.end()));
  EXPECT_THROW(ExtractLytroFile(dir / "bad.lfp", dir / "out"), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST(ContainerInfo, LooksLikeLytroFile) {
  TempDir dir;
  WriteBytes(dir / "a.png", "\x89PNG\r\n\x1a\n....");
  WriteBytes(dir / "b.json", "{\"views\": 3}");
  WriteBytes(dir / "c.RAW", "xx");  // no partner
  EXPECT_FALSE(LooksLikeLytroFile(dir / "a.png"));
  EXPECT_FALSE(LooksLikeLytroFile(dir / "b.json"));
  EXPECT_FALSE(LooksLikeLytroFile(dir / "c.RAW"));
  EXPECT_FALSE(LooksLikeLytroFile(dir / "missing.lfp"));
  EXPECT_FALSE(LooksLikeLytroFile(dir.path()));
}

TEST(InfoCli, RealContainersExitZeroWithSectionCounts) {
  LFSP_REQUIRE_SHARED_DATA(data);
  for (const Expected& e : kReal) {
    SCOPED_TRACE(e.name);
    const auto result = RunLfsp({"info", (data / "lytro" / e.name).string()});
    EXPECT_EQ(result.exit_status, 0) << result.err;
    EXPECT_NE(result.out.find("sections     " + std::to_string(e.sections) + " (1 LFM, " +
                              std::to_string(e.sections - 1) + " LFC), every SHA-1 verified"),
              std::string::npos)
        << result.out;
  }
  const auto json = RunLfsp({"info", "--json", (data / "lytro" / "illum_demo.LFP").string()});
  ASSERT_EQ(json.exit_status, 0) << json.err;
  const nlohmann::json parsed = nlohmann::json::parse(json.out);
  EXPECT_EQ(parsed["sections"].size(), 12u);
  EXPECT_EQ(parsed["metadata"]["lens"]["zoom_step"], 123);
  const auto txt = RunLfsp({"info", (data / "lytro" / "illum_whiteimage_metadata.TXT").string()});
  EXPECT_EQ(txt.exit_status, 0) << txt.err;
  EXPECT_NE(txt.out.find("B01, serial B5143909630"), std::string::npos) << txt.out;
}

TEST(InfoCli, ExtractOption) {
  LFSP_REQUIRE_SHARED_DATA(data);
  TempDir dir;
  const auto result =
      RunLfsp({"info", (data / "lytro" / "IMG_0002-dm.lfp").string(), "--extract", (dir / "dm").string()});
  ASSERT_EQ(result.exit_status, 0) << result.err;
  const DisparityMap depth = ReadPfm(dir / "dm" / "depth_map_00.pfm");
  EXPECT_EQ(depth.width(), 330);
  EXPECT_TRUE(std::filesystem::exists(dir / "dm" / "confidence_map_00.pfm"));
}

TEST(InfoCli, CorruptContainersExitTwoWithOneLine) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const std::string good = ReadBytes(data / "lytro" / "illum_demo.LFP");
  TempDir dir;
  std::string flipped = good;
  flipped[40000] = static_cast<char>(flipped[40000] ^ 0x01);  // inside section 2's payload
  std::string magic = good;
  magic[2] = 'X';
  std::string long_length = good;
  long_length[16 + 12] = '\x7f';
  const std::pair<const char*, std::string> cases[] = {{"truncated.LFP", good.substr(0, 300000)},
                                                       {"flipped.LFP", flipped},
                                                       {"magic.LFP", magic},
                                                       {"length.LFP", long_length},
                                                       {"empty.lfp", ""}};
  const std::pair<const char*, const char*> expected[] = {
      {"truncated.LFP", "past the end"},
      {"flipped.LFP", "section 2 at byte offset 34176: SHA-1 mismatch"},
      {"magic.LFP", "wrong file magic"},
      {"length.LFP", "section 0 at byte offset 16"},
      {"empty.lfp", "truncated LFP file"}};
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    const auto path = dir / cases[i].first;
    WriteBytes(path, cases[i].second);
    const auto result = RunLfsp({"info", path.string(), "--extract", (dir / "never").string()});
    EXPECT_EQ(result.exit_status, 2) << cases[i].first;
    EXPECT_EQ(Lines(result.err), 1u) << result.err;
    EXPECT_EQ(result.err.rfind("lfsp: error: " + path.string(), 0), 0u) << result.err;
    EXPECT_NE(result.err.find(expected[i].second), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "never"));
  }
}

TEST(DecodeCli, RealContainersHaveNoRawImage) {
  LFSP_REQUIRE_SHARED_DATA(data);
  TempDir dir;
  for (const Expected& e : kReal) {
    const auto result = RunLfsp({"decode", (data / "lytro" / e.name).string(), "--out", (dir / "lf.h5").string()});
    EXPECT_EQ(result.exit_status, 2) << e.name;
    EXPECT_EQ(Lines(result.err), 1u) << result.err;
    EXPECT_NE(result.err.find("no raw image"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "lf.h5"));
  }
}

}  // namespace
}  // namespace lfsp::decode
