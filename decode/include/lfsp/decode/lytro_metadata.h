#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode {

// The Bayer pattern named by its top-left 2x2 tile, read row by row (F01
// "BGGR", Illum "GRBG").
enum class BayerPattern { kRGGB, kGRBG, kGBRG, kBGGR };
std::string_view ToString(BayerPattern pattern);
// "rggb", "GRBG", ... (any case); lfsp::Error for anything else.
BayerPattern BayerPatternFromString(const std::string& name);

// One value per Bayer channel, as Lytro stores levels and gains: {r, gr, gb,
// b}.
struct BayerValues {
  double r = 0.0;
  double gr = 0.0;
  double gb = 0.0;
  double b = 0.0;
  friend bool operator==(const BayerValues&, const BayerValues&) = default;
};

// Everything a decoder needs to read the raw sensor buffer. F01 and white-image
// TXT files keep it under image.rawDetails.{pixelPacking, pixelFormat, mosaic};
// Illum LFR files directly under image.*.
struct RawFormat {
  int width = 0;
  int height = 0;
  RawPacking packing = RawPacking::kBits12BigEndian;
  BayerValues black;  // pixelFormat.black
  BayerValues white;  // pixelFormat.white
  int right_shift = 0;
  BayerPattern mosaic = BayerPattern::kBGGR;
};

// The micro-lens array as the camera describes it (devices.mla +
// devices.sensor.pixelPitch).
struct MlaDescription {
  double lens_pitch = 0.0;   // m
  double pixel_pitch = 0.0;  // m (devices.sensor.pixelPitch)
  double rotation = 0.0;     // rad; positive = clockwise viewed from the front
  double scale_x = 1.0;      // scaleFactor.x
  double scale_y = 1.0;      // scaleFactor.y
  double offset_x = 0.0;     // sensorOffset.{x,y,z}, m
  double offset_y = 0.0;
  double offset_z = 0.0;
  std::string tiling;  // "hexUniformRowMajor"
  std::string config;  // "com.lytro.mla.3"

  double ApproxSpacingPixels() const { return lens_pitch / pixel_pitch; }  // ~9.93 (F01) / ~14.29 (Illum)
};

// Colour processing the camera intends (F01 image.color.ccmRgbToSrgbArray /
// Illum image.color.ccm, row-major M with out = M * in; white-balance gains;
// gamma; the sensor's normalised responses for white images).
struct ColourDescription {
  std::optional<std::array<double, 9>> ccm;
  std::optional<BayerValues> white_balance_gain;
  std::optional<double> gamma;
  std::optional<BayerValues> normalized_response;  // devices.sensor.normalizedResponses[0]
  std::optional<double> normalized_response_cct;
  // Illum: the camera's auto white balance (algorithms.awb.computed.{gain, cct}) and its colour matrices per
  // colour temperature (devices.sensor.perCcm[] {cct, ccm}), sorted by cct.
  std::optional<BayerValues> awb_gain;
  std::optional<double> awb_cct;
  struct CcmAtTemperature {
    double cct = 0.0;
    std::array<double, 9> ccm{};
  };
  std::vector<CcmAtTemperature> per_ccm;
};

// The metadata of one frame (a capture or a white image), independent of the
// schema it came from. Optional fields are absent in some files; the Require*
// accessors throw lfsp::Error naming the source and the missing field when a
// caller truly needs them.
struct LytroMetadata {
  std::string source;  // file (and section) the metadata was read from, for messages
  std::string schema;  // "F01 frame", "Illum frame", "white-image TXT"

  std::string camera_make;
  std::string camera_model;  // "F01", "ILLUM", "B01" (Illum white images)
  std::string firmware;
  std::string serial;         // privateMetadata.camera.serialNumber ("" if absent)
  std::string sensor_serial;  // privateMetadata.devices.sensor.{serialNumber|sensorSerial}

  std::optional<int> zoom_step;
  std::optional<int> focus_step;
  std::optional<double> exposure_duration;  // s, devices.shutter.frameExposureDuration
  std::optional<double> iso;
  std::optional<double> f_number;
  std::optional<double> focal_length;  // m
  std::optional<double> modulation_exposure_bias;
  std::optional<double> limit_exposure_bias;

  std::optional<RawFormat> raw_format;  // set when every raw field was found
  std::string raw_format_problem;       // otherwise, the first missing/invalid field
  std::optional<MlaDescription> mla;
  std::string mla_problem;
  ColourDescription colour;

  bool modulation_frame = false;  // a white ("modulation") image (com.lytro.tags.modulationFrame)
  bool dark_frame = false;

  nlohmann::json frame_metadata = nlohmann::json::object();    // the source JSON, as read
  nlohmann::json private_metadata = nlohmann::json::object();  // may be empty

  const RawFormat& RequireRawFormat() const;
  const MlaDescription& RequireMla() const;
  int RequireZoomStep() const;
  int RequireFocusStep() const;
};

// Reads frame metadata in any of the known schemas: an F01 or Illum frame
// metadata object (the section behind frame.metadataRef, or inline
// frame.metadata) and, optionally, the private metadata object. `source` names
// the origin in messages. Throws lfsp::Error if `frame_metadata` is not an
// object or a present field has the wrong type (a missing optional field is not
// an error).
LytroMetadata ParseFrameMetadata(const nlohmann::json& frame_metadata, const nlohmann::json& private_metadata,
                                 const std::string& source);

// Reads a stand-alone metadata document: a white-image .TXT
// (master.picture.frameArray[0].frame.{metadata, privateMetadata}, trailing
// bytes after the last '}' ignored), a bare frame metadata .json (as extracted
// by lfpsplitter/imageio, e.g. IMG_0001__frame.json), or an LFP table of
// contents with inline frame metadata.
LytroMetadata ParseMetadataDocument(std::string_view text, const std::string& source);
LytroMetadata ReadMetadataFile(const std::filesystem::path& path);

}  // namespace lfsp::decode
