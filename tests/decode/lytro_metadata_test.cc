// The metadata model against the real F01 frame metadata, the real Illum white-image TXT and the Illum container's
// inline metadata: every value is the one in the file. Missing or mistyped fields give one clear lfsp::Error.

#include "lfsp/decode/lytro_metadata.h"

#include <gtest/gtest.h>

#include "lfsp/core/error.h"
#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/lytro_capture.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

using lfsp::testing::ErrorOf;
using lfsp::testing::LoadJson;
using lfsp::testing::ReadBytes;
using lfsp::testing::TempDir;
using lfsp::testing::WriteBytes;

constexpr double kExact = 1e-12;  // values are copied, not computed

TEST(LytroMetadataReal, F01FrameMetadata) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroMetadata md = ReadMetadataFile(data / "lytro" / "f01_frame_metadata.json");
  EXPECT_EQ(md.schema, "F01 frame");
  EXPECT_EQ(md.camera_make, "Lytro, Inc.");
  EXPECT_EQ(md.camera_model, "F01");
  EXPECT_EQ(md.zoom_step, 981);
  EXPECT_EQ(md.focus_step, 582);
  EXPECT_NEAR(*md.exposure_duration, 0.01433531753718853, kExact);
  EXPECT_NEAR(*md.iso, 200, kExact);
  EXPECT_NEAR(*md.modulation_exposure_bias, -1.1242823600769043, kExact);
  const RawFormat& raw = md.RequireRawFormat();
  EXPECT_EQ(raw.width, 3280);
  EXPECT_EQ(raw.height, 3280);
  EXPECT_EQ(raw.packing, RawPacking::kBits12BigEndian);
  EXPECT_EQ(raw.mosaic, BayerPattern::kBGGR);  // tile r,gr:gb,b with upper-left b
  EXPECT_EQ(raw.black, (BayerValues{168, 168, 168, 168}));
  EXPECT_EQ(raw.white, (BayerValues{4095, 4095, 4095, 4095}));
  const MlaDescription& mla = md.RequireMla();
  EXPECT_NEAR(mla.lens_pitch, 1.389859962463379e-05, kExact);
  EXPECT_NEAR(mla.pixel_pitch, 1.3999999761581417e-06, kExact);
  EXPECT_NEAR(mla.rotation, 0.0019290975760668516, kExact);
  EXPECT_NEAR(mla.scale_y, 1.0004994869232178, kExact);
  EXPECT_NEAR(mla.offset_x, -2.7138671874999998e-06, kExact);
  EXPECT_NEAR(mla.offset_z, 2.5e-05, kExact);
  EXPECT_EQ(mla.tiling, "hexUniformRowMajor");
  EXPECT_NEAR(mla.ApproxSpacingPixels(), 9.93, 0.005);  // lytro-format.md: ~9.93 px
  ASSERT_TRUE(md.colour.ccm.has_value());
  EXPECT_NEAR((*md.colour.ccm)[0], 3.1115827560424805, kExact);
  EXPECT_NEAR((*md.colour.ccm)[8], 2.0768373012542725, kExact);
  EXPECT_NEAR(*md.colour.gamma, 0.41666001081466675, kExact);
  EXPECT_NEAR(md.colour.white_balance_gain->b, 1.72265625, kExact);
  EXPECT_FALSE(md.modulation_frame);
}

TEST(LytroMetadataReal, IllumWhiteImageTxt) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroMetadata md = ReadMetadataFile(data / "lytro" / "illum_whiteimage_metadata.TXT");
  EXPECT_EQ(md.schema, "white-image TXT");
  EXPECT_EQ(md.camera_model, "B01");
  EXPECT_EQ(md.serial, "B5143909630");
  EXPECT_EQ(md.sensor_serial, "0x0c220593");
  EXPECT_EQ(md.zoom_step, -1040);
  EXPECT_EQ(md.focus_step, -300);
  EXPECT_NEAR(*md.exposure_duration, 0.0072242450714111329, kExact);
  EXPECT_TRUE(md.modulation_frame);
  EXPECT_FALSE(md.dark_frame);
  const RawFormat& raw = md.RequireRawFormat();  // from ...metadata.image.rawDetails
  EXPECT_EQ(raw.width, 7728);
  EXPECT_EQ(raw.height, 5368);
  EXPECT_EQ(raw.packing, RawPacking::kBits10Illum);
  EXPECT_EQ(raw.mosaic, BayerPattern::kGRBG);
  EXPECT_EQ(raw.black.gr, 64);
  EXPECT_EQ(raw.white.b, 1023);
  EXPECT_NEAR(md.RequireMla().rotation, -0.00055235880427062511, kExact);
  EXPECT_NEAR(md.RequireMla().ApproxSpacingPixels(), 14.2857, 1e-3);
  EXPECT_NEAR(md.colour.normalized_response->r, 0.77616631984710693, kExact);
  EXPECT_NEAR(md.colour.normalized_response->b, 0.73449766635894775, kExact);
  EXPECT_NEAR(*md.colour.normalized_response_cct, 5100, kExact);
  EXPECT_NEAR((*md.colour.ccm)[0], 2.4827811717987061, kExact);
}

TEST(LytroMetadataReal, TxtWithTrailingBytesAfterTheLastBrace) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const std::string text = ReadBytes(data / "lytro" / "illum_whiteimage_metadata.TXT");
  const std::string with_tail = text + std::string("\0\0\x07junk 12", 10);
  const LytroMetadata md = ParseMetadataDocument(with_tail, "MOD_0000.TXT");
  EXPECT_EQ(md.serial, "B5143909630");
  EXPECT_EQ(md.RequireRawFormat().width, 7728);
}

TEST(LytroMetadataReal, IllumContainerInlineMetadataUsesImageNotRawDetails) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LytroCapture capture = OpenLytroCapture(data / "lytro" / "illum_demo.LFP");
  ASSERT_TRUE(capture.metadata.has_value()) << capture.metadata_problem;
  const LytroMetadata& md = *capture.metadata;
  EXPECT_EQ(md.schema, "Illum frame");
  EXPECT_EQ(md.camera_model, "ILLUM");
  EXPECT_EQ(md.serial, "45142500380");
  EXPECT_EQ(md.sensor_serial, "0B320406");
  EXPECT_EQ(md.zoom_step, 123);
  EXPECT_EQ(md.focus_step, 814);
  EXPECT_NEAR(*md.iso, 122, kExact);
  EXPECT_NEAR(*md.modulation_exposure_bias, 0.2447252869606018, kExact);
  const RawFormat& raw = md.RequireRawFormat();
  EXPECT_EQ(raw.packing, RawPacking::kBits10Illum);
  EXPECT_EQ(raw.mosaic, BayerPattern::kGRBG);
  EXPECT_EQ(raw.black, (BayerValues{64, 64, 64, 64}));
  EXPECT_NEAR((*md.colour.ccm)[0], 2.244826316833496, kExact);  // image.color.ccm (no ccmRgbToSrgbArray)
  EXPECT_NEAR(md.colour.white_balance_gain->r, 1.0875036716461182, kExact);
  EXPECT_NEAR(md.RequireMla().scale_y, 1.0003466606140137, kExact);
  EXPECT_NEAR(md.RequireMla().offset_y, 6.261034965515137e-06, kExact);
  ASSERT_TRUE(md.colour.awb_gain.has_value());
  EXPECT_NEAR(md.colour.awb_gain->b, 1.6269161701202393, kExact);
  EXPECT_NEAR(*md.colour.awb_cct, 3505, kExact);
  ASSERT_EQ(md.colour.per_ccm.size(), 3u);
  EXPECT_NEAR(md.colour.per_ccm[0].cct, 2850, kExact);
  EXPECT_NEAR(md.colour.per_ccm[2].cct, 6500, kExact);
  EXPECT_NEAR(md.colour.per_ccm[1].ccm[0], 2.4793264865875244, kExact);
  EXPECT_NEAR(md.colour.per_ccm[2].ccm[8], 1.8904708623886108, kExact);
}

TEST(LytroMetadata, MosaicFromTileAndUpperLeftPixel) {
  nlohmann::json m = {{"image",
                       {{"width", 4},
                        {"height", 2},
                        {"rawDetails",
                         {{"pixelPacking", {{"bitsPerPixel", 12}, {"endianness", "big"}}},
                          {"pixelFormat",
                           {{"black", {{"r", 1}, {"gr", 1}, {"gb", 1}, {"b", 1}}},
                            {"white", {{"r", 9}, {"gr", 9}, {"gb", 9}, {"b", 9}}}}},
                          {"mosaic", {{"tile", "r,gr:gb,b"}, {"upperLeftPixel", "r"}}}}}}}};
  const std::pair<const char*, BayerPattern> cases[] = {
      {"r", BayerPattern::kRGGB}, {"gr", BayerPattern::kGRBG}, {"gb", BayerPattern::kGBRG}, {"b", BayerPattern::kBGGR}};
  for (const auto& [upper_left, expected] : cases) {
    m["image"]["rawDetails"]["mosaic"]["upperLeftPixel"] = upper_left;
    EXPECT_EQ(ParseFrameMetadata(m, {}, "t").RequireRawFormat().mosaic, expected) << upper_left;
  }
}

TEST(LytroMetadataBadInput, MissingNeededFieldsNameTheField) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const nlohmann::json good = LoadJson(data / "lytro" / "f01_frame_metadata.json");

  nlohmann::json no_packing = good;
  no_packing["image"]["rawDetails"].erase("pixelPacking");
  const LytroMetadata md1 = ParseFrameMetadata(no_packing, {}, "IMG_0001.json");
  EXPECT_FALSE(md1.raw_format.has_value());
  EXPECT_NE(ErrorOf([&] { md1.RequireRawFormat(); })
                .find("IMG_0001.json: metadata field "
                      "image.rawDetails.pixelPacking.bitsPerPixel is missing"),
            std::string::npos);

  nlohmann::json no_pitch = good;
  no_pitch["devices"]["mla"].erase("lensPitch");
  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(no_pitch, {}, "f").RequireMla(); }).find("devices.mla.lensPitch"),
            std::string::npos);

  nlohmann::json no_zoom = good;
  no_zoom["devices"]["lens"].erase("zoomStep");
  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(no_zoom, {}, "f").RequireZoomStep(); }).find("devices.lens.zoomStep"),
            std::string::npos);

  nlohmann::json no_black = good;
  no_black["image"]["rawDetails"]["pixelFormat"]["black"].erase("gr");
  EXPECT_NE(ErrorOf([&] {
              ParseFrameMetadata(no_black, {}, "f").RequireRawFormat();
            }).find("image.rawDetails.pixelFormat.black.gr is missing"),
            std::string::npos);
}

TEST(LytroMetadataBadInput, WrongTypesAndValues) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const nlohmann::json good = LoadJson(data / "lytro" / "f01_frame_metadata.json");
  nlohmann::json zoom_text = good;
  zoom_text["devices"]["lens"]["zoomStep"] = "far";
  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(zoom_text, {}, "f.json"); }).find("devices.lens.zoomStep is not a number"),
            std::string::npos);

  nlohmann::json packing = good;
  packing["image"]["rawDetails"]["pixelPacking"]["bitsPerPixel"] = 14;
  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(packing, {}, "f").RequireRawFormat(); }).find("unsupported raw packing"),
            std::string::npos);

  nlohmann::json levels = good;
  levels["image"]["rawDetails"]["pixelFormat"]["white"]["gr"] = 100;  // below black 168
  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(levels, {}, "f").RequireRawFormat(); }).find("not above the black"),
            std::string::npos);

  nlohmann::json size = good;
  size["image"]["width"] = -3280;
  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(size, {}, "f").RequireRawFormat(); }).find("not a valid size"),
            std::string::npos);

  EXPECT_NE(ErrorOf([&] { ParseFrameMetadata(nlohmann::json::array(), {}, "f"); }).find("not a JSON object"),
            std::string::npos);
}

TEST(LytroMetadataBadInput, DocumentsThatAreNotMetadata) {
  EXPECT_NE(ErrorOf([&] { ParseMetadataDocument("no json here", "a.TXT"); }).find("a.TXT"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseMetadataDocument("{\"a\": }", "b.TXT"); }).find("b.TXT: not valid JSON"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ParseMetadataDocument("{\"hello\": 1}", "c.json"); }).find("not Lytro frame metadata"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ParseMetadataDocument(R"({"master":{"picture":{"frameArray":[{"frame":{}}]}}})", "d.TXT");
            }).find("master.picture.frameArray[0].frame.metadata is missing"),
            std::string::npos);
  TempDir dir;
  EXPECT_NE(ErrorOf([&] { ReadMetadataFile(dir / "MOD_0000.TXT"); }).find("no such file"), std::string::npos);
}

}  // namespace
}  // namespace lfsp::decode
