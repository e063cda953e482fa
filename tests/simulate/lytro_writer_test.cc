// The writers produce files the decode stage reads back exactly (all SHA-1s verified), with metadata whose key
// paths match the real Lytro files in ../shared/data/lytro.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "lfsp/core/error.h"
#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/lytro_capture.h"
#include "lfsp/simulate/lytro_writer.h"
#include "lfsp/simulate/raw_capture.h"
#include "test_support.h"

namespace lfsp::simulate {
namespace {

using nlohmann::json;

// Every key path of a JSON document, arrays collapsed to "[]" (so "frames[].frame.imageRef").
void CollectPaths(const json& value, const std::string& prefix, std::set<std::string>& out) {
  if (value.is_object()) {
    for (auto it = value.begin(); it != value.end(); ++it) {
      const std::string path = prefix.empty() ? it.key() : prefix + "." + it.key();
      out.insert(path);
      CollectPaths(it.value(), path, out);
    }
  } else if (value.is_array()) {
    for (const auto& element : value) CollectPaths(element, prefix + "[]", out);
  }
}

std::set<std::string> Paths(const json& value) {
  std::set<std::string> out;
  CollectPaths(value, "", out);
  return out;
}

std::string Difference(const std::set<std::string>& a, const std::set<std::string>& b) {
  std::string text;
  for (const auto& p : a)
    if (!b.count(p)) text += " " + p;
  return text;
}

json ReadJsonFile(const std::filesystem::path& path) {
  std::string text = testing::ReadBytes(path);
  text = text.substr(0, text.rfind('}') + 1);  // white-image TXT files may carry trailing bytes
  return json::parse(text);
}

json TocOf(const std::filesystem::path& path) {
  const decode::LfpContainer container = decode::ReadLfpContainer(path);
  return container.Toc(path.string()).Json(path.string());
}

RawCapture SmallCapture(const CameraModel& camera) {
  CaptureOptions options;
  options.seed = 3;
  options.hot_pixels = 3;
  return RenderRawCapture(BuiltinScene("planes"), camera, options);
}

TEST(LytroWriter, CapturesParseBackExactlyWithEveryShaVerified) {
  for (const std::string name : {"mini-illum", "mini-f01"}) {
    SCOPED_TRACE(name);
    const CameraModel camera = CameraPreset(name);
    const RawCapture raw = SmallCapture(camera);
    const std::vector<std::uint8_t> bytes = decode::SerializeLfpContainer(BuildCaptureContainer(camera, raw));
    const decode::LytroCapture capture = decode::OpenLytroContainerBytes(bytes, name);  // verifies every SHA-1
    ASSERT_TRUE(capture.metadata.has_value()) << capture.metadata_problem;
    const decode::LytroMetadata& m = *capture.metadata;
    const decode::RawFormat& format = m.RequireRawFormat();
    EXPECT_EQ(format.width, camera.sensor_width);
    EXPECT_EQ(format.height, camera.sensor_height);
    EXPECT_EQ(format.packing, PackingFor(camera));
    EXPECT_EQ(format.mosaic, camera.bayer == "grbg" ? decode::BayerPattern::kGRBG : decode::BayerPattern::kBGGR);
    EXPECT_EQ(format.black.gr, camera.black);
    EXPECT_EQ(format.white.b, camera.white);
    EXPECT_EQ(m.camera_model, camera.model);
    EXPECT_EQ(m.serial, camera.serial);
    EXPECT_EQ(m.RequireZoomStep(), raw.setting.zoom_step);
    EXPECT_EQ(m.RequireFocusStep(), raw.setting.focus_step);
    const decode::MlaDescription& mla = m.RequireMla();
    EXPECT_DOUBLE_EQ(mla.lens_pitch, camera.lens_pitch);
    EXPECT_DOUBLE_EQ(mla.rotation, camera.rotation);
    EXPECT_DOUBLE_EQ(mla.scale_y, camera.scale_y);
    ASSERT_TRUE(m.colour.normalized_response || camera.model == "F01");
    EXPECT_FALSE(capture.IsWhiteImage());
    const decode::RawImage back = capture.ReadRawImage();
    EXPECT_EQ(back.pixels, raw.pixels) << "packing round trip must be exact";
    // A corrupted payload byte must be caught by the SHA-1 check.
    std::vector<std::uint8_t> corrupt = bytes;
    corrupt[corrupt.size() / 2] ^= 0x01;
    EXPECT_THROW(decode::OpenLytroContainerBytes(corrupt, name), Error);
  }
}

TEST(LytroWriter, WhiteImagesReadBackAsRawTxtPairs) {
  testing::TempDir dir;
  for (const std::string name : {"mini-illum", "mini-f01"}) {
    const CameraModel camera = CameraPreset(name);
    const RawCapture white = RenderWhiteImage(camera, 1, 9);
    const auto path = dir / (name + "_MOD_0001.RAW");
    WriteWhiteImage(camera, white, path);
    const decode::LytroCapture capture = decode::OpenLytroCapture(path);
    EXPECT_TRUE(capture.IsWhiteImage()) << name;
    ASSERT_TRUE(capture.metadata.has_value()) << capture.metadata_problem;
    EXPECT_EQ(capture.metadata->RequireZoomStep(), camera.white_settings[1].zoom_step);
    EXPECT_EQ(capture.metadata->RequireFocusStep(), camera.white_settings[1].focus_step);
    EXPECT_EQ(capture.ReadRawImage().pixels, white.pixels) << name;
  }
}

TEST(LytroWriter, MetadataKeyPathsMatchTheRealFiles) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const auto lytro = data / "lytro";
  const CameraModel illum = CameraPreset("illum");
  const CameraModel f01 = CameraPreset("f01");
  RawCapture illum_raw;  // metadata only needs sizes and the lens setting: no need to render 41 Mpixels
  illum_raw.width = illum.sensor_width;
  illum_raw.height = illum.sensor_height;
  illum_raw.setting = illum.white_settings[3];
  illum_raw.exposure = 0.7;
  RawCapture f01_raw = illum_raw;
  f01_raw.width = f01.sensor_width;
  f01_raw.height = f01.sensor_height;
  f01_raw.setting = f01.white_settings[1];

  // Illum frame metadata vs the real LFR's frames[0].frame.metadata.
  const json demo = TocOf(lytro / "illum_demo.LFP");
  const auto real_illum = Paths(demo["frames"][0]["frame"]["metadata"]);
  const auto ours_illum = Paths(IllumFrameMetadata(illum, illum_raw));
  EXPECT_EQ(ours_illum, real_illum) << "missing:" << Difference(real_illum, ours_illum)
                                    << "\nextra:" << Difference(ours_illum, real_illum);
  // Private metadata.
  EXPECT_EQ(Paths(PrivateMetadata(illum)), Paths(demo["frames"][0]["frame"]["privateMetadata"]));

  // F01 frame metadata vs the real F01 frame JSON.
  const auto real_f01 = Paths(ReadJsonFile(lytro / "f01_frame_metadata.json"));
  const auto ours_f01 = Paths(F01FrameMetadata(f01, f01_raw));
  EXPECT_EQ(ours_f01, real_f01) << "missing:" << Difference(real_f01, ours_f01)
                                << "\nextra:" << Difference(ours_f01, real_f01);

  // White-image TXT vs the real Illum MOD TXT.
  RawCapture white = illum_raw;
  white.setting = illum.white_settings[0];
  const auto real_white = Paths(ReadJsonFile(lytro / "illum_whiteimage_metadata.TXT"));
  const auto ours_white = Paths(WhiteImageMetadata(illum, white));
  EXPECT_EQ(ours_white, real_white) << "missing:" << Difference(real_white, ours_white)
                                    << "\nextra:" << Difference(ours_white, real_white);
}

TEST(LytroWriter, TablesOfContentsUseTheRealSchemas) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const auto lytro = data / "lytro";
  // Illum: same top-level keys as a real LFR table of contents; frames[0].frame holds the three references.
  const CameraModel mini_illum = CameraPreset("mini-illum");
  const decode::LfpContainer illum = BuildCaptureContainer(mini_illum, SmallCapture(mini_illum));
  const json illum_toc = illum.Toc("illum").Json("illum");
  const json demo = TocOf(lytro / "illum_demo.LFP");
  std::set<std::string> ours, real;
  for (auto it = illum_toc.begin(); it != illum_toc.end(); ++it) ours.insert(it.key());
  for (auto it = demo.begin(); it != demo.end(); ++it) real.insert(it.key());
  EXPECT_EQ(ours, real);
  for (const char* ref : {"imageRef", "metadataRef", "privateMetadataRef"})
    EXPECT_NE(illum.Find(illum_toc["frames"][0]["frame"][ref].get<std::string>()), nullptr) << ref;
  EXPECT_EQ(illum.sections.back().kind, decode::SectionKind::kMetadata) << "Illum camera files end with the LFM";
  // F01: every key path we write exists in a real F01 table of contents.
  const CameraModel mini_f01 = CameraPreset("mini-f01");
  const decode::LfpContainer f01 = BuildCaptureContainer(mini_f01, SmallCapture(mini_f01));
  const json f01_toc = f01.Toc("f01").Json("f01");
  const auto real_f01 = Paths(TocOf(lytro / "IMG_0001-stk.lfp"));
  const auto ours_f01 = Paths(f01_toc);
  EXPECT_EQ(Difference(ours_f01, real_f01), "");
  EXPECT_EQ(f01.sections.front().kind, decode::SectionKind::kMetadata) << "F01 files start with the LFM";
}

}  // namespace
}  // namespace lfsp::simulate
