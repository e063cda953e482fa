#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/decode/lfp_container.h"
#include "lfsp/decode/raw_packing.h"
#include "lfsp/simulate/lenslet_camera.h"
#include "lfsp/simulate/raw_capture.h"

namespace lfsp::simulate {

// Metadata in the cameras' own schemas, field names and nesting as in the real files (../shared/data/lytro):
//   Illum: frames[0].frame.metadata of an LFR (public schema 1.3.4: image.pixelPacking, image.pixelFormat, ...)
//   F01:   the frame metadata behind picture.frameArray[0].frame.metadataRef (image.rawDetails.*)
//   white images: the MOD_####.TXT document (master.picture.frameArray[0].frame.{metadata, privateMetadata})
nlohmann::json IllumFrameMetadata(const CameraModel& camera, const RawCapture& raw);
nlohmann::json F01FrameMetadata(const CameraModel& camera, const RawCapture& raw);
nlohmann::json FrameMetadata(const CameraModel& camera, const RawCapture& raw);  // by camera.model
nlohmann::json PrivateMetadata(const CameraModel& camera);
nlohmann::json WhiteImageMetadata(const CameraModel& camera, const RawCapture& white);

decode::RawPacking PackingFor(const CameraModel& camera);  // 12-bit big-endian (F01) or Illum 10-bit

// The capture as a container: Illum LFR (content sections, then the table of contents with frames[]) or F01 LFP
// (table of contents with picture.frameArray first, then content).
decode::LfpContainer BuildCaptureContainer(const CameraModel& camera, const RawCapture& raw);
std::string CaptureFileName(const CameraModel& camera);  // "capture.LFR" / "capture.lfp"

// The capture's Bayer mosaic as the real F01 frames of Tao et al. (../shared/data/lytro_raw) were exported: the raw
// codes scaled to 8 bits (code x 255 / white level, so the black level stays in the data) and stored as a greyscale
// JPEG with libjpeg's standard tables at `quality` (those frames: 75); beside it the same 8-bit mosaic as a lossless
// PNG (same name, .png), the baseline that shows what the JPEG alone costs. Written atomically. lfsp::Error for a
// quality outside 1..100.
void WriteMosaicJpeg(const CameraModel& camera, const RawCapture& raw, const std::filesystem::path& path, int quality);
inline constexpr const char* kMosaicJpegName = "capture_mosaic.jpg";

// MOD_####.RAW (packed like the capture) and MOD_####.TXT beside it, each written atomically.
void WriteWhiteImage(const CameraModel& camera, const RawCapture& white, const std::filesystem::path& raw_path);

// Ground-truth lenslet geometry: the exact lattice, an LFToolbox-style grid model, the decoded grid and how it maps
// to the sensor, hot pixels, levels and responses.
nlohmann::json LensletGeometryJson(const CameraModel& camera, const RawCapture& raw);

}  // namespace lfsp::simulate
