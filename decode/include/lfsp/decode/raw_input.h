#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "lfsp/decode/lytro_metadata.h"
#include "lfsp/decode/raw_packing.h"
#include "lfsp/decode/white_balance.h"

namespace lfsp::decode {

// What a greyscale JPEG mosaic's restoration takes for colourless: the sensor's flat mosaic, or the scene's grey (the
// white balance of a short first restoration, which the decode's automatic white balance then applies as well).
enum class JpegGrey { kSensor, kScene };
std::string_view ToString(JpegGrey grey);
// "sensor" or "scene"; lfsp::Error naming the option otherwise.
JpegGrey JpegGreyFromString(const std::string& name);

// How to read a Bayer mosaic that comes in an ordinary image file, without Lytro metadata.
struct PlainRawOptions {
  std::string camera;                 // "f01" or "illum": sensor layout and optics (NominalMetadata); "" = unknown
  std::optional<BayerPattern> bayer;  // overrides the camera's pattern
  std::optional<double> black;        // overrides the black level (raw code)
  std::optional<double> white;        // overrides the white (saturation) level (raw code)
  // Greyscale JPEG mosaics: iterations of RestoreJpegMosaic (jpeg_mosaic.h); 0 = the plain JPEG decode.
  int jpeg_restore_iterations = 30;
  // Greyscale JPEG mosaics with a camera: the colour the restoration takes for none (MosaicRestoreOptions::grey_gains).
  JpegGrey jpeg_grey = JpegGrey::kSensor;
};

// What a decoder (and the simulator) needs to know about each Lytro camera, as the real files state it (F01:
// ../shared/data/lytro/f01_frame_metadata.json; Illum: illum_demo.LFP and its white-image TXT).
struct CameraFacts {
  const char* model;  // "F01", "ILLUM"
  BayerPattern mosaic;
  int bits;
  double black;        // raw code
  double white;        // raw code
  double lens_pitch;   // m
  double pixel_pitch;  // m
  double rotation;     // rad, devices.mla.rotation
  double scale_y;      // devices.mla.scaleFactor.y
  std::array<double, 9> ccm;
  BayerValues white_balance;                       // image.color.whiteBalanceGain
  std::optional<BayerValues> normalized_response;  // devices.sensor.normalizedResponses (white-image TXT)
  std::optional<double> gamma;
};
// "f01" or "illum" (any case); lfsp::Error naming `source` otherwise.
const CameraFacts& NominalCameraFacts(const std::string& camera, const std::string& source);

// The nominal metadata of a Lytro camera ("f01" or "illum", case-insensitive) for a width x height sensor: raw
// levels, Bayer pattern, micro-lens pitch and rotation, colour matrix and white balance, as real files of that
// camera state them. The micro-lens array is taken as centred (no sensor offset). lfsp::Error naming `source` for
// an unknown camera.
LytroMetadata NominalMetadata(const std::string& camera, int width, int height, const std::string& source);

// A raw lenslet image in hand, from any input the decoder reads.
struct RawInput {
  std::filesystem::path path;
  std::string format;  // "LFP container", "raw + metadata pair", "plain raw image (8-bit PNG)", ...
  RawImage raw;
  LytroMetadata metadata;            // from the file, or NominalMetadata for a plain image
  bool white_image = false;          // a Lytro modulation (white) image
  bool has_camera_metadata = false;  // false: a plain image without --camera (no optics, no colour)
  std::string levels;                // where the black and white levels came from, for the one-line report
  nlohmann::json jpeg_restoration;   // what RestoreJpegMosaic did (null: not a greyscale JPEG, or not asked)
  // The automatic white balance a greyscale JPEG's restoration took its grey from (PlainRawOptions::jpeg_grey scene):
  // the decode's kAuto white balance applies the same (DecodeOptions::estimated_white_balance).
  std::optional<AutoWhiteBalanceReport> jpeg_scene_grey;
  int jpeg_block = 0;           // a mosaic stored as JPEG: its block size in pixels (8); 0 for lossless files
  double unpack_seconds = 0.0;  // of the time to open it, unpacking the raw packing into 16-bit samples
};

// True for the extensions of plain raw images: .png .tif .tiff .jpg .jpeg (any case).
bool IsPlainRawImagePath(const std::filesystem::path& path);

// A single-channel 8- or 16-bit PNG, TIFF or JPEG holding a Bayer mosaic (or a grey image: RGB files with three
// equal channels count as one). A greyscale JPEG's mosaic is restored from its DCT coefficients (RestoreJpegMosaic),
// unless options.jpeg_restore_iterations is 0. Levels: --black/--white when given; otherwise, with a camera, 16-bit
// files whose largest code fits under the camera's white level keep the camera's levels (a sensor dump) and other
// files are taken as the camera's raw scaled to the file's full range (the black level scales with it); without a
// camera, the file's full code range (0..255 or 0..65535). lfsp::Error naming the file for colour or float images and
// for levels out of range.
RawInput ReadPlainRawImage(const std::filesystem::path& path, const PlainRawOptions& options);

// Any raw input: a Lytro capture or white image (LFP/LFR container, .RAW + metadata pair), or a plain raw image.
// Plain options other than `camera` apply to plain images only; lfsp::Error naming the file when there is no raw
// image or no metadata to read it.
RawInput OpenRawInput(const std::filesystem::path& path, const PlainRawOptions& options = {});

}  // namespace lfsp::decode
