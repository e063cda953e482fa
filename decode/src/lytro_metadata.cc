#include "lfsp/decode/lytro_metadata.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "json_text.h"
#include "lfsp/core/error.h"
#include "lfsp/core/json_fields.h"
#include "lfsp/decode/lfp_container.h"

namespace lfsp::decode {
namespace {

BayerValues ReadBayerValues(const nlohmann::json& root, const std::string& path, const std::string& source,
                            std::string_view prefix) {
  BayerValues v;
  v.r = RequireNumber(root, path + ".r", source, prefix);
  v.gr = RequireNumber(root, path + ".gr", source, prefix);
  v.gb = RequireNumber(root, path + ".gb", source, prefix);
  v.b = RequireNumber(root, path + ".b", source, prefix);
  return v;
}

RawPacking PackingFrom(int bits, const std::string& endianness, const std::string& source, const std::string& at) {
  if (bits == 12 && endianness == "big") return RawPacking::kBits12BigEndian;
  if (bits == 10 && endianness == "little") return RawPacking::kBits10Illum;
  if (bits == 16 && endianness == "little") return RawPacking::kBits16LittleEndian;
  throw Error(source + ": unsupported raw packing at " + at + ": " + std::to_string(bits) + " bits, " + endianness +
              "-endian (known: 12-bit big, 10-bit little, 16-bit little)");
}

// The mosaic as Lytro writes it: a 2x2 tile "r,gr:gb,b" (rows separated by ':')
// and the tile entry found at the sensor's top-left pixel. The pattern is the
// tile rotated so that entry comes first.
BayerPattern MosaicFrom(const std::string& tile, const std::string& upper_left, const std::string& source) {
  std::string cells[2][2];
  {
    const std::size_t colon = tile.find(':');
    const std::string rows[2] = {tile.substr(0, colon), colon == std::string::npos ? "" : tile.substr(colon + 1)};
    for (int r = 0; r < 2; ++r) {
      const std::size_t comma = rows[r].find(',');
      if (comma == std::string::npos) throw Error(source + ": cannot read mosaic tile \"" + tile + "\"");
      cells[r][0] = rows[r].substr(0, comma);
      cells[r][1] = rows[r].substr(comma + 1);
    }
  }
  for (int ty = 0; ty < 2; ++ty) {
    for (int tx = 0; tx < 2; ++tx) {
      if (cells[ty][tx] != upper_left) continue;
      std::string letters;
      for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) {
          const std::string& c = cells[(ty + i) % 2][(tx + j) % 2];
          letters += c == "r" ? 'R' : c == "b" ? 'B' : (c == "gr" || c == "gb") ? 'G' : '?';
        }
      }
      if (letters == "RGGB") return BayerPattern::kRGGB;
      if (letters == "GRBG") return BayerPattern::kGRBG;
      if (letters == "GBRG") return BayerPattern::kGBRG;
      if (letters == "BGGR") return BayerPattern::kBGGR;
    }
  }
  throw Error(source + ": unsupported mosaic tile \"" + tile + "\" with upper-left pixel \"" + upper_left + "\"");
}

// F01 and white-image TXT files describe the raw buffer under image.rawDetails;
// Illum LFR files directly under image (lytro-format.md §1.3). Throws
// lfsp::Error naming the first missing or invalid field.
RawFormat ReadRawFormat(const nlohmann::json& m, const std::string& source) {
  const std::string base = FindPath(m, "image.rawDetails") != nullptr ? "image.rawDetails" : "image";
  RawFormat f;
  const double width = RequireNumber(m, "image.width", source);
  const double height = RequireNumber(m, "image.height", source);
  if (!(width >= 1 && height >= 1 && width <= 1e5 && height <= 1e5) || width != std::floor(width) ||
      height != std::floor(height)) {
    throw Error(source + ": raw image size " + std::to_string(width) + "x" + std::to_string(height) +
                " in image.width/height is not a valid size");
  }
  f.width = static_cast<int>(width);
  f.height = static_cast<int>(height);
  const int bits = RequireInt(m, base + ".pixelPacking.bitsPerPixel", source);
  const std::string endianness = RequireString(m, base + ".pixelPacking.endianness", source);
  f.packing = PackingFrom(bits, endianness, source, base + ".pixelPacking");
  f.black = ReadBayerValues(m, base + ".pixelFormat.black", source, "");
  f.white = ReadBayerValues(m, base + ".pixelFormat.white", source, "");
  if (!(f.white.gr > f.black.gr && f.white.r > f.black.r && f.white.b > f.black.b && f.white.gb > f.black.gb)) {
    throw Error(source + ": " + base + ".pixelFormat white level is not above the black level");
  }
  f.right_shift = IntAt(m, base + ".pixelFormat.rightShift", source).value_or(0);
  f.mosaic = MosaicFrom(RequireString(m, base + ".mosaic.tile", source),
                        RequireString(m, base + ".mosaic.upperLeftPixel", source), source);
  return f;
}

MlaDescription ReadMla(const nlohmann::json& m, const std::string& source) {
  MlaDescription mla;
  mla.lens_pitch = RequireNumber(m, "devices.mla.lensPitch", source);
  mla.pixel_pitch = RequireNumber(m, "devices.sensor.pixelPitch", source);
  if (!(mla.lens_pitch > 0 && mla.pixel_pitch > 0)) {
    throw Error(source +
                ": devices.mla.lensPitch and "
                "devices.sensor.pixelPitch must be positive");
  }
  mla.rotation = RequireNumber(m, "devices.mla.rotation", source);
  mla.scale_x = NumberAt(m, "devices.mla.scaleFactor.x", source).value_or(1.0);
  mla.scale_y = NumberAt(m, "devices.mla.scaleFactor.y", source).value_or(1.0);
  mla.offset_x = NumberAt(m, "devices.mla.sensorOffset.x", source).value_or(0.0);
  mla.offset_y = NumberAt(m, "devices.mla.sensorOffset.y", source).value_or(0.0);
  mla.offset_z = NumberAt(m, "devices.mla.sensorOffset.z", source).value_or(0.0);
  mla.tiling = StringAt(m, "devices.mla.tiling", source).value_or("");
  mla.config = StringAt(m, "devices.mla.config", source).value_or("");
  return mla;
}

std::array<double, 9> ReadCcm(const nlohmann::json& ccm, const std::string& source, const std::string& path) {
  if (!ccm.is_array() || ccm.size() != 9) throw Error(source + ": " + path + " is not an array of 9 numbers");
  std::array<double, 9> values{};
  for (std::size_t i = 0; i < 9; ++i) {
    if (!ccm[i].is_number()) throw Error(source + ": " + path + " is not an array of 9 numbers");
    values[i] = ccm[i].get<double>();
  }
  return values;
}

ColourDescription ReadColour(const nlohmann::json& m, const std::string& source) {
  ColourDescription c;
  if (const nlohmann::json* ccm = FindPath(m, "image.color.ccmRgbToSrgbArray"); ccm != nullptr) {
    c.ccm = ReadCcm(*ccm, source, "image.color.ccmRgbToSrgbArray");
  } else if (const nlohmann::json* illum_ccm = FindPath(m, "image.color.ccm"); illum_ccm != nullptr) {
    c.ccm = ReadCcm(*illum_ccm, source, "image.color.ccm");
  }
  if (FindPath(m, "algorithms.awb.computed.gain") != nullptr) {
    c.awb_gain = ReadBayerValues(m, "algorithms.awb.computed.gain", source, "");
    c.awb_cct = NumberAt(m, "algorithms.awb.computed.cct", source);
  }
  if (const nlohmann::json* per = FindPath(m, "devices.sensor.perCcm"); per != nullptr && per->is_array()) {
    for (std::size_t i = 0; i < per->size(); ++i) {
      const std::string path = "devices.sensor.perCcm[" + std::to_string(i) + "]";
      ColourDescription::CcmAtTemperature entry;
      entry.cct = RequireNumber(m, path + ".cct", source);
      entry.ccm = ReadCcm((*per)[i].contains("ccm") ? (*per)[i]["ccm"] : nlohmann::json(), source, path + ".ccm");
      c.per_ccm.push_back(entry);
    }
    std::sort(c.per_ccm.begin(), c.per_ccm.end(), [](const auto& a, const auto& b) { return a.cct < b.cct; });
  }
  if (FindPath(m, "image.color.whiteBalanceGain") != nullptr) {
    c.white_balance_gain = ReadBayerValues(m, "image.color.whiteBalanceGain", source, "");
  }
  c.gamma = NumberAt(m, "image.color.gamma", source);
  if (FindPath(m, "devices.sensor.normalizedResponses[0]") != nullptr) {
    c.normalized_response = ReadBayerValues(m, "devices.sensor.normalizedResponses[0]", source, "");
    c.normalized_response_cct = NumberAt(m, "devices.sensor.normalizedResponses[0].cct", source);
  }
  return c;
}

std::optional<int> StepAt(const nlohmann::json& m, std::string_view path, const std::string& source) {
  const std::optional<double> value = NumberAt(m, path, source);
  if (!value) return std::nullopt;
  if (!(std::abs(*value) < 1e9)) throw Error(source + ": metadata field " + std::string(path) + " is out of range");
  return static_cast<int>(std::lround(*value));
}

}  // namespace

BayerPattern BayerPatternFromString(const std::string& name) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const BayerPattern pattern :
       {BayerPattern::kRGGB, BayerPattern::kGRBG, BayerPattern::kGBRG, BayerPattern::kBGGR})
    if (ToString(pattern) == upper) return pattern;
  throw Error("Bayer pattern '" + name + "': unknown (expected rggb, grbg, gbrg or bggr)");
}

std::string_view ToString(BayerPattern pattern) {
  switch (pattern) {
    case BayerPattern::kRGGB:
      return "RGGB";
    case BayerPattern::kGRBG:
      return "GRBG";
    case BayerPattern::kGBRG:
      return "GBRG";
    case BayerPattern::kBGGR:
      return "BGGR";
  }
  return "?";
}

const RawFormat& LytroMetadata::RequireRawFormat() const {
  if (!raw_format) {
    throw Error(raw_format_problem.empty() ? source + ": no raw image format in the metadata" : raw_format_problem);
  }
  return *raw_format;
}

const MlaDescription& LytroMetadata::RequireMla() const {
  if (!mla) throw Error(mla_problem.empty() ? source + ": no micro-lens array description" : mla_problem);
  return *mla;
}

int LytroMetadata::RequireZoomStep() const {
  if (!zoom_step) throw Error(source + ": metadata field devices.lens.zoomStep is missing");
  return *zoom_step;
}

int LytroMetadata::RequireFocusStep() const {
  if (!focus_step) throw Error(source + ": metadata field devices.lens.focusStep is missing");
  return *focus_step;
}

LytroMetadata ParseFrameMetadata(const nlohmann::json& frame_metadata, const nlohmann::json& private_metadata,
                                 const std::string& source) {
  if (!frame_metadata.is_object()) throw Error(source + ": frame metadata is not a JSON object");
  const nlohmann::json& m = frame_metadata;
  LytroMetadata md;
  md.source = source;
  md.frame_metadata = frame_metadata;
  md.private_metadata = private_metadata.is_object() ? private_metadata : nlohmann::json::object();
  md.schema = FindPath(m, "image.rawDetails") != nullptr ? "F01 frame" : "Illum frame";

  md.camera_make = StringAt(m, "camera.make", source).value_or("");
  md.camera_model = StringAt(m, "camera.model", source).value_or("");
  md.firmware = StringAt(m, "camera.firmware", source).value_or("");
  md.serial = StringAt(md.private_metadata, "camera.serialNumber", source).value_or("");
  md.sensor_serial = StringAt(md.private_metadata, "devices.sensor.serialNumber", source)
                         .value_or(StringAt(md.private_metadata, "devices.sensor.sensorSerial", source).value_or(""));

  md.zoom_step = StepAt(m, "devices.lens.zoomStep", source);
  md.focus_step = StepAt(m, "devices.lens.focusStep", source);
  md.exposure_duration = NumberAt(m, "devices.shutter.frameExposureDuration", source);
  md.iso = NumberAt(m, "image.iso", source);
  if (!md.iso) md.iso = NumberAt(m, "devices.sensor.iso", source);
  md.f_number = NumberAt(m, "devices.lens.fNumber", source);
  md.focal_length = NumberAt(m, "devices.lens.focalLength", source);
  md.modulation_exposure_bias = NumberAt(m, "image.modulationExposureBias", source);
  md.limit_exposure_bias = NumberAt(m, "image.limitExposureBias", source);

  // The raw format and the MLA are needed only to decode; a file without them
  // (a focus-stack export) is still described, so their problems are kept and
  // raised by RequireRawFormat / RequireMla.
  try {
    md.raw_format = ReadRawFormat(m, source);
  } catch (const Error& e) {
    md.raw_format_problem = e.what();
  }
  try {
    md.mla = ReadMla(m, source);
  } catch (const Error& e) {
    md.mla_problem = e.what();
  }
  md.colour = ReadColour(m, source);
  return md;
}

LytroMetadata ParseMetadataDocument(std::string_view text, const std::string& source) {
  const nlohmann::json doc = ParseLytroJson(text, source);
  // White-image TXT: master.picture.frameArray[0].{frame.{metadata,
  // privateMetadata}, parameters}.
  if (const nlohmann::json* frame = FindPath(doc, "master.picture.frameArray[0]"); frame != nullptr) {
    const nlohmann::json* metadata = FindPath(*frame, "frame.metadata");
    if (metadata == nullptr) {
      throw Error(source +
                  ": metadata field "
                  "master.picture.frameArray[0].frame.metadata is missing");
    }
    const nlohmann::json* priv = FindPath(*frame, "frame.privateMetadata");
    LytroMetadata md = ParseFrameMetadata(*metadata, priv ? *priv : nlohmann::json::object(), source);
    md.schema = "white-image TXT";
    const nlohmann::json* t = FindPath(*frame, "parameters.vendorContent");
    if (t != nullptr && t->is_object() && t->contains("com.lytro.tags")) {
      const nlohmann::json& lytro_tags = (*t)["com.lytro.tags"];
      md.modulation_frame = BoolAt(lytro_tags, "modulationFrame", source).value_or(false);
      md.dark_frame = BoolAt(lytro_tags, "darkFrame", source).value_or(false);
    }
    return md;
  }
  // A table of contents with inline metadata (Lytro Desktop exports):
  // frames[0].frame.metadata.
  if (const nlohmann::json* metadata = FindPath(doc, "frames[0].frame.metadata"); metadata != nullptr) {
    const nlohmann::json* priv = FindPath(doc, "frames[0].frame.privateMetadata");
    return ParseFrameMetadata(*metadata, priv ? *priv : nlohmann::json::object(), source);
  }
  // A bare frame metadata object (IMG_0001__frame.json).
  if (doc.contains("image") || doc.contains("devices")) {
    return ParseFrameMetadata(doc, nlohmann::json::object(), source);
  }
  throw Error(source +
              ": not Lytro frame metadata (no "
              "master.picture.frameArray, frames[0].frame.metadata, "
              "image or devices)");
}

LytroMetadata ReadMetadataFile(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  return ParseMetadataDocument(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                               path.string());
}

}  // namespace lfsp::decode
