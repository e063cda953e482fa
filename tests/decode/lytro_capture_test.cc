// Opening Lytro inputs: what the real containers hold (by reference path), synthetic F01 / Illum captures built with
// the writer (both schemas, raw image resolved and unpacked exactly), raw + TXT pairs and calibration archives.

#include "lfsp/decode/lytro_capture.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "lfsp/core/error.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

using lfsp::testing::ErrorOf;
using lfsp::testing::LoadJson;
using lfsp::testing::ReadBytes;
using lfsp::testing::TempDir;
using lfsp::testing::WriteBytes;

std::vector<std::uint16_t> RandomPixels(std::size_t n, int max_value, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint16_t> pixels(n);
  for (auto& p : pixels) p = static_cast<std::uint16_t>(rng() % static_cast<std::uint32_t>(max_value + 1));
  return pixels;
}

std::vector<float> Floats(const std::vector<std::uint8_t>& payload) {
  std::vector<float> values(payload.size() / 4);
  std::memcpy(values.data(), payload.data(), values.size() * 4);
  return values;
}

std::size_t PresentCount(const LytroCapture& c, ItemKind kind) {
  std::size_t n = 0;
  for (const EmbeddedItem* item : c.ItemsOf(kind)) n += item->present() ? 1 : 0;
  return n;
}

TEST(LytroCaptureReal, F01FocusStackExport) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroCapture c = OpenLytroCapture(data / "lytro" / "IMG_0001-stk.lfp");
  EXPECT_EQ(c.schema, "F01 picture (picture.frameArray)");
  EXPECT_EQ(PresentCount(c, ItemKind::kFocusStackImage), 12u);
  ASSERT_EQ(PresentCount(c, ItemKind::kDepthLut), 1u);
  const EmbeddedItem& lut = *c.ItemsOf(ItemKind::kDepthLut)[0];
  EXPECT_EQ(lut.width, 20);
  EXPECT_EQ(lut.height, 20);
  EXPECT_EQ(c.container.sections[static_cast<std::size_t>(lut.section)].payload.size(), 20u * 20u * 4u);
  for (const EmbeddedItem* frame : c.ItemsOf(ItemKind::kFocusStackImage)) {
    EXPECT_EQ(frame->representation, "jpeg");
    EXPECT_EQ(frame->width, 1080);
    EXPECT_EQ(c.container.sections[static_cast<std::size_t>(frame->section)].payload[0], 0xFF);  // JPEG SOI
  }
  // The raw image and frame metadata are referenced but not in a Desktop export.
  EXPECT_FALSE(c.HasRawImage());
  ASSERT_EQ(c.ItemsOf(ItemKind::kRawImage).size(), 1u);
  EXPECT_FALSE(c.ItemsOf(ItemKind::kRawImage)[0]->present());
  EXPECT_FALSE(c.metadata.has_value());
  EXPECT_NE(c.metadata_problem.find("not in this file"), std::string::npos);
  EXPECT_TRUE(c.UnreferencedSections().empty());
  const std::string message = ErrorOf([&] { (void)c.RawBytes(); });
  EXPECT_NE(message.find("no raw image"), std::string::npos) << message;
  EXPECT_NE(message.find("12 focus-stack frames"), std::string::npos) << message;
}

TEST(LytroCaptureReal, F01DepthMapIsFloat32WithinTheLambdaRange) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroCapture c = OpenLytroCapture(data / "lytro" / "IMG_0002-dm.lfp");
  ASSERT_EQ(PresentCount(c, ItemKind::kDepthMap), 1u);
  ASSERT_EQ(PresentCount(c, ItemKind::kConfidenceMap), 1u);
  const EmbeddedItem& depth = *c.ItemsOf(ItemKind::kDepthMap)[0];
  EXPECT_EQ(depth.width, 330);
  EXPECT_EQ(depth.height, 330);
  // vendorContent.minLambda / maxLambda = -20 / 11: every depth value must lie inside if read as float32 LE.
  const auto values = Floats(c.container.sections[static_cast<std::size_t>(depth.section)].payload);
  ASSERT_EQ(values.size(), 330u * 330u);
  for (const float v : values) ASSERT_TRUE(v >= -20.0f && v <= 11.0f) << v;
  EXPECT_TRUE(c.UnreferencedSections().empty());
}

TEST(LytroCaptureReal, F01H264Export) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroCapture c = OpenLytroCapture(data / "lytro" / "IMG_0002-stk.lfp");
  EXPECT_EQ(PresentCount(c, ItemKind::kImageBlock), 2u);
  for (const EmbeddedItem* block : c.ItemsOf(ItemKind::kImageBlock)) EXPECT_EQ(block->representation, "h264");
  EXPECT_EQ(PresentCount(c, ItemKind::kDepthLut), 1u);
  EXPECT_FALSE(c.HasRawImage());
}

TEST(LytroCaptureReal, IllumDesktopExport) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroCapture c = OpenLytroCapture(data / "lytro" / "illum_demo.LFP");
  EXPECT_EQ(c.schema, "Illum picture (frames[])");
  EXPECT_EQ(PresentCount(c, ItemKind::kFocusStackImage), 10u);
  ASSERT_EQ(PresentCount(c, ItemKind::kDepthMap), 1u);
  const EmbeddedItem& depth = *c.ItemsOf(ItemKind::kDepthMap)[0];
  EXPECT_EQ(depth.width, 88);
  EXPECT_EQ(depth.height, 60);
  EXPECT_EQ(depth.representation, "packedFloat");
  const auto values = Floats(c.container.sections[static_cast<std::size_t>(depth.section)].payload);
  ASSERT_EQ(values.size(), 88u * 60u);
  for (const float v : values) ASSERT_TRUE(v >= -15.0f && v <= 12.5f) << v;  // depthMap.minLambda / maxLambda
  EXPECT_FALSE(c.HasRawImage());
  EXPECT_TRUE(c.ItemsOf(ItemKind::kRawImage).empty());  // no imageRef at all
  EXPECT_NE(ErrorOf([&] { (void)c.ReadRawImage(); }).find("no raw image"), std::string::npos);
}

// Builds a small capture in the real layout of each camera, from the real metadata with a reduced sensor size.
struct Synthetic {
  LfpContainer container;
  std::vector<std::uint16_t> pixels;
};

Synthetic F01Capture(const nlohmann::json& real_metadata, int width, int height) {
  Synthetic s;
  nlohmann::json md = real_metadata;
  md["image"]["width"] = width;
  md["image"]["height"] = height;
  s.pixels = RandomPixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 4095, 3);
  LfpContainer content;
  const std::string image = content.AddBinary(PackRaw(RawPacking::kBits12BigEndian, s.pixels, "t"));
  const std::string meta = content.AddJson(md);
  const std::string priv = content.AddJson({{"camera", {{"serialNumber", "A123"}}}});
  const nlohmann::json toc = {
      {"picture",
       {{"frameArray",
         {{{"frame", {{"metadataRef", meta}, {"privateMetadataRef", priv}, {"imageRef", image}}},
           {"parameters",
            {{"vendorContent", {{"com.lytro.tags", {{"darkFrame", false}, {"modulationFrame", false}}}}}}}}}}}},
      {"version", {{"major", 1}, {"minor", 0}}}};
  s.container.AddJson(toc, SectionKind::kMetadata);  // F01 puts the LFM first
  for (auto& section : content.sections) s.container.sections.push_back(std::move(section));
  return s;
}

Synthetic IllumCapture(const nlohmann::json& inline_metadata, int width, int height) {
  Synthetic s;
  nlohmann::json md = inline_metadata;
  md["image"]["width"] = width;
  md["image"]["height"] = height;
  s.pixels = RandomPixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 1023, 4);
  const std::string image = s.container.AddBinary(PackRaw(RawPacking::kBits10Illum, s.pixels, "t"));
  const std::string meta = s.container.AddJson(md);
  const std::string priv = s.container.AddJson({{"camera", {{"serialNumber", "B5000000001"}}}});
  const std::string hot = s.container.AddBinary({1, 0, 0, 0, 7, 0, 9, 0});
  const nlohmann::json toc = {
      {"frames",
       {{{"frame",
          {{"imageRef", image}, {"metadataRef", meta}, {"privateMetadataRef", priv}, {"hotPixelRef", hot}}}}}}};
  s.container.AddJson(toc, SectionKind::kMetadata);  // Illum puts the LFM last
  return s;
}

TEST(LytroCaptureSynthetic, F01SchemaResolvesMetadataAndUnpacksTheRawImage) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const Synthetic s = F01Capture(LoadJson(data / "lytro" / "f01_frame_metadata.json"), 33, 7);
  const auto bytes = SerializeLfpContainer(s.container);
  const LytroCapture c = OpenLytroContainerBytes(bytes, "IMG_9999.lfp");
  ASSERT_TRUE(c.metadata.has_value()) << c.metadata_problem;
  EXPECT_EQ(c.metadata->camera_model, "F01");
  EXPECT_EQ(c.metadata->serial, "A123");
  EXPECT_EQ(c.metadata->zoom_step, 981);
  EXPECT_TRUE(c.HasRawImage());
  EXPECT_FALSE(c.IsWhiteImage());
  const RawImage raw = c.ReadRawImage();
  EXPECT_EQ(raw.width, 33);
  EXPECT_EQ(raw.height, 7);
  EXPECT_EQ(raw.pixels, s.pixels);
  EXPECT_TRUE(c.UnreferencedSections().empty());
}

TEST(LytroCaptureSynthetic, IllumSchemaWithLfmLastAndMetadataRef) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroCapture real = OpenLytroCapture(data / "lytro" / "illum_demo.LFP");
  const Synthetic s = IllumCapture(real.metadata->frame_metadata, 31, 5);
  TempDir dir;
  WriteLfpContainer(s.container, dir / "IMG_0001.LFR");
  const LytroCapture c = OpenLytroCapture(dir / "IMG_0001.LFR");
  EXPECT_EQ(c.container.FindToc(), &c.container.sections.back());
  ASSERT_TRUE(c.metadata.has_value()) << c.metadata_problem;
  EXPECT_EQ(c.metadata->camera_model, "ILLUM");
  EXPECT_EQ(c.metadata->serial, "B5000000001");
  EXPECT_EQ(c.ReadRawImage().pixels, s.pixels);
  EXPECT_EQ(c.ItemsOf(ItemKind::kOther).size(), 1u);  // hotPixelRef
  EXPECT_EQ(c.ItemsOf(ItemKind::kOther)[0]->json_path, "frames[0].frame.hotPixelRef");
}

TEST(LytroCaptureSynthetic, RawBufferOfTheWrongSizeIsAnError) {
  LFSP_REQUIRE_SHARED_DATA(data);
  nlohmann::json md = LoadJson(data / "lytro" / "f01_frame_metadata.json");
  Synthetic s = F01Capture(md, 10, 10);
  // Claim a bigger sensor than the buffer holds.
  LfpContainer c = s.container;
  nlohmann::json toc = c.sections[0].Json("t");
  md["image"]["width"] = 12;
  md["image"]["height"] = 10;
  const std::string meta = c.AddJson(md);
  toc["picture"]["frameArray"][0]["frame"]["metadataRef"] = meta;
  c.sections[0] = LfpSection{};
  const std::string text = toc.dump();
  c.sections[0].kind = SectionKind::kMetadata;
  c.sections[0].payload.assign(text.begin(), text.end());
  const LytroCapture capture = OpenLytroContainerBytes(SerializeLfpContainer(c), "wrong.lfp");
  const std::string message = ErrorOf([&] { (void)capture.ReadRawImage(); });
  EXPECT_NE(message.find("wrong.lfp raw image: raw buffer of 150 bytes, expected 180 bytes"), std::string::npos)
      << message;
}

TEST(LytroCapturePair, WhiteImageRawWithTxtBeside) {
  LFSP_REQUIRE_SHARED_DATA(data);
  TempDir dir;
  std::string txt = ReadBytes(data / "lytro" / "illum_whiteimage_metadata.TXT");
  nlohmann::json doc = nlohmann::json::parse(txt);
  auto& image = doc["master"]["picture"]["frameArray"][0]["frame"]["metadata"]["image"];
  image["width"] = 13;
  image["height"] = 3;
  const auto pixels = RandomPixels(39, 1023, 5);
  WriteBytes(dir / "MOD_0007.TXT", doc.dump(1, '\t') + std::string("\0\0\x1a", 3));  // trailing bytes
  const auto packed = PackRaw(RawPacking::kBits10Illum, pixels, "t");
  WriteBytes(dir / "MOD_0007.RAW", std::string(packed.begin(), packed.end()));
  for (const char* open : {"MOD_0007.RAW", "MOD_0007.TXT"}) {
    const LytroCapture c = OpenLytroCapture(dir / open);
    EXPECT_EQ(c.format, "raw + metadata pair");
    EXPECT_TRUE(c.IsWhiteImage());
    EXPECT_TRUE(c.HasRawImage());
    EXPECT_EQ(c.metadata->serial, "B5143909630");
    EXPECT_EQ(c.ReadRawImage().pixels, pixels);
  }
}

TEST(LytroCapturePair, RawWithoutMetadataOrOfWrongSize) {
  TempDir dir;
  WriteBytes(dir / "MOD_0001.RAW", std::string(10, '\0'));
  EXPECT_NE(ErrorOf([&] { OpenLytroCapture(dir / "MOD_0001.RAW"); }).find("raw file without its metadata"),
            std::string::npos);
  LFSP_REQUIRE_SHARED_DATA(data);
  std::filesystem::copy_file(data / "lytro" / "illum_whiteimage_metadata.TXT", dir / "MOD_0001.TXT");
  const LytroCapture c = OpenLytroCapture(dir / "MOD_0001.RAW");
  const std::string message = ErrorOf([&] { (void)c.ReadRawImage(); });
  EXPECT_NE(message.find("raw buffer of 10 bytes, expected 51854880 bytes"), std::string::npos) << message;
}

TEST(LytroCapturePair, SplitterFrameWithPrivateMetadataBeside) {
  LFSP_REQUIRE_SHARED_DATA(data);
  TempDir dir;
  nlohmann::json md = LoadJson(data / "lytro" / "f01_frame_metadata.json");
  md["image"]["width"] = 5;
  md["image"]["height"] = 3;
  WriteBytes(dir / "IMG_0001__frame.json", md.dump());
  WriteBytes(dir / "IMG_0001__private.json", R"({"camera": {"serialNumber": "A302130521"}})");
  const auto pixels = RandomPixels(15, 4095, 9);
  const auto packed = PackRaw(RawPacking::kBits12BigEndian, pixels, "t");
  WriteBytes(dir / "IMG_0001__frame.raw", std::string(packed.begin(), packed.end()));
  const LytroCapture c = OpenLytroCapture(dir / "IMG_0001__frame.raw");
  EXPECT_EQ(c.metadata->serial, "A302130521");
  EXPECT_EQ(c.metadata->camera_model, "F01");
  EXPECT_EQ(c.ReadRawImage().pixels, pixels);
}

TEST(LytroCaptureArchive, CalibrationFilesAreListedByName) {
  LfpContainer c;
  const std::string raw = c.AddBinary({1, 2, 3, 4, 5});
  const std::string txt = c.AddBinary({'{', '}'});
  c.AddJson({{"files",
              {{{"name", "C:\\T1CALIB\\MOD_0000.RAW"}, {"dataRef", raw}},
               {{"name", "C:\\T1CALIB\\MOD_0000.TXT"}, {"dataRef", txt}}}},
             {"nextFile", "data.C.1"}},
            SectionKind::kMetadata);
  const LytroCapture capture = OpenLytroContainerBytes(SerializeLfpContainer(c), "data.C.0");
  EXPECT_EQ(capture.schema, "calibration archive (files[])");
  const auto files = capture.ItemsOf(ItemKind::kCalibrationFile);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0]->name, "C:\\T1CALIB\\MOD_0000.RAW");
  EXPECT_TRUE(files[0]->present());
  EXPECT_FALSE(capture.HasRawImage());
}

TEST(LytroCaptureBadInput, DamagedContainerIsAnError) {
  TempDir dir;
  WriteBytes(dir / "x.lfp", "\x89LFP\r\n\x1a\n");
  EXPECT_NE(ErrorOf([&] { OpenLytroCapture(dir / "x.lfp"); }).find("truncated"), std::string::npos);
  WriteBytes(dir / "y.lfr", "this is not a container at all");
  EXPECT_NE(ErrorOf([&] { OpenLytroCapture(dir / "y.lfr"); }).find("wrong file magic"), std::string::npos);
}

}  // namespace
}  // namespace lfsp::decode
