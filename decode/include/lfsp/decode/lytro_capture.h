#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/lytro_metadata.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode {

// What a reference in a Lytro table of contents points at.
enum class ItemKind {
  kRawImage,         // frame.imageRef: the raw sensor image
  kWhiteImage,       // frame.modulationDataRef, or the imageRef of a modulation frame (a white image)
  kFrameMetadata,    // frame.metadataRef (JSON)
  kPrivateMetadata,  // frame.privateMetadataRef (JSON)
  kDepthMap,         // float32 little-endian depth (lambda) map
  kConfidenceMap,    // float32 little-endian confidence of the depth map
  kDepthLut,         // F01 refocus-stack depth look-up table (float32 little-endian)
  kFocusStackImage,  // one frame of a refocus / focus stack (JPEG)
  kImageBlock,       // a block of images (H.264 stream)
  kThumbnail,        // JPEG thumbnail
  kCalibrationFile,  // files[].dataRef of a calibration archive data.C.N
  kOther,            // any other *Ref (hot pixels, geometry correction, histograms, ...)
};
std::string_view ToString(ItemKind kind);

// One reference found in the table of contents (or the raw file of a raw + metadata pair).
struct EmbeddedItem {
  ItemKind kind = ItemKind::kOther;
  std::string json_path;  // where the reference sits, e.g. "frames[0].frame.imageRef"
  std::string reference;  // "sha1-<hex>"
  int section = -1;       // index into LytroCapture::container.sections; -1 if this file does not hold it
  std::string name;       // calibration files: the archived name; focus stacks: "lambda -8.92"
  int width = 0;          // from the metadata, when given
  int height = 0;
  std::string representation;  // "jpeg", "raw", "packedFloat", "h264", ... when given
  bool present() const { return section >= 0; }
};

// An opened Lytro input: an LFP/LFR container (capture, Desktop export or calibration archive), a raw + metadata
// pair (.RAW with a .TXT or .json of the same stem beside it, e.g. MOD_0000.RAW + MOD_0000.TXT), or a metadata
// document on its own.
struct LytroCapture {
  std::filesystem::path path;
  std::string format;      // "LFP container", "raw + metadata pair", "metadata document"
  std::string schema;      // "Illum picture (frames[])", "F01 picture (picture.frameArray)", "calibration archive
                           // (files[])", "white-image TXT", ...
  LfpContainer container;  // containers only
  nlohmann::json toc = nlohmann::json::object();  // the LFM of a container, or the metadata document
  std::optional<LytroMetadata> metadata;          // the frame metadata, when the file holds it
  std::string metadata_problem;                   // otherwise, why not (e.g. a dangling metadataRef)
  std::vector<EmbeddedItem> items;
  std::filesystem::path raw_path;            // pairs: the .RAW file
  std::vector<std::uint8_t> raw_pair_bytes;  // pairs: its bytes

  // True when the sensor image itself is in hand (a capture's raw image or a white image's raw buffer).
  bool HasRawImage() const;
  const EmbeddedItem* FrameImage() const;  // the item holding that image, or nullptr (pairs: the .RAW item)
  bool IsWhiteImage() const;               // the raw buffer is a white (modulation) image
  // The packed bytes of the raw image; lfsp::Error "<path>: no raw image ..." (saying what the file does hold)
  // when there is none.
  std::span<const std::uint8_t> RawBytes() const;
  // Unpacks the raw image with the metadata's geometry and packing (lfsp::Error if either is missing or the
  // buffer has the wrong size).
  RawImage ReadRawImage() const;

  std::vector<const EmbeddedItem*> ItemsOf(ItemKind kind) const;
  std::vector<std::size_t> UnreferencedSections() const;  // sections no reference points at (besides the TOC)
  std::string HoldsSummary() const;                       // "12 focus-stack JPEG frames, 1 depth LUT 20x20"
};

// Opens any Lytro input (see LytroCapture). Containers are fully verified (every SHA-1). Throws lfsp::Error naming
// the file on any problem. References the file does not hold (Desktop exports drop the raw image and frame
// metadata) are not errors: they are listed as items with section = -1.
LytroCapture OpenLytroCapture(const std::filesystem::path& path);
// The same for a container already in memory (fuzzing, tests).
LytroCapture OpenLytroContainerBytes(std::span<const std::uint8_t> bytes, const std::string& source_name);

// The partner metadata file of a .RAW (same stem, .TXT/.txt/.json/.JSON), or empty if none.
std::filesystem::path FindMetadataPartner(const std::filesystem::path& raw_path);

}  // namespace lfsp::decode
