// Raw lenslet images from every input the decoder reads: Lytro files with their metadata, and plain image files
// holding a Bayer mosaic with a camera's nominal metadata.

#include "lfsp/decode/raw_input.h"

#include <spdlog/fmt/fmt.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/decode/jpeg_mosaic.h"
#include "lfsp/decode/lytro_capture.h"
#include "lfsp/decode/white_balance.h"

namespace lfsp::decode {
namespace {

std::string Lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

BayerValues Uniform(double value) { return {value, value, value, value}; }

std::string Extension(const std::filesystem::path& path) { return Lower(path.extension().string()); }

bool IsJpegPath(const std::filesystem::path& path) {
  const std::string extension = Extension(path);
  return extension == ".jpg" || extension == ".jpeg";
}

struct PlainLevels {
  double black = 0.0;  // file codes
  double white = 0.0;
  std::string why;
};

// The levels of a plain raw image when none are given.
//   16-bit, camera given, every code under the camera's white level: a sensor dump, read with the camera's levels.
//   Camera given otherwise: the file is the camera's raw scaled to the file's range (an 8-bit export, or a 16-bit
//     one scaled up), so the camera's black level scales with it (F01: 168 of 4095 is 10.46 of 255). Leaving it at 0
//     keeps a pedestal that the white balance then tints (blue on an F01: its blue gain is the largest).
//   No camera: the file's full code range.
PlainLevels DefaultPlainLevels(int bit_depth, std::uint16_t largest_stored, bool has_camera, const RawFormat& camera) {
  const double full_scale = bit_depth == 8 ? 255.0 : 65535.0;
  if (!has_camera) return {0.0, full_scale, "the file's full code range"};
  if (bit_depth == 16 && largest_stored <= camera.white.gr)
    return {
        camera.black.gr, camera.white.gr,
        "the camera's levels (codes fit its " + std::to_string(static_cast<int>(camera.white.gr)) + " white level)"};
  return {camera.black.gr / camera.white.gr * full_scale, full_scale,
          "the camera's black level scaled to the file's full code range"};
}

// Rounds of the short first restoration that only finds a greyscale JPEG's white balance (below). The estimate moves
// with them (IMG_2's blue gain: 1.07 after 3 rounds, 1.12 after 10, 1.21 after 30). From 10, the real F01 frames'
// colour bands read 2.08 / 2.60 / 2.07 (IMG_1-3) against 2.25 / 2.21 / 2.09 from 30, the simulated JPEG captures
// read better (two-horses 25.81 against 25.64 dB, the leaves capture's bands 3.40 against 3.89), and it costs half
// as much (BENCHMARKS.md, forty-second session).
constexpr int kWhiteBalanceRestoreIterations = 10;

// A greyscale JPEG mosaic's scene grey (`--jpeg-grey scene`): the decode's automatic white balance, estimated on the
// mosaic (EstimateMosaicWhiteBalance) of a short restoration about the sensor's grey. Not on the plain JPEG decode,
// which has lost the colour the estimate votes with; not on a restoration about the scene's grey, which shows the
// scene's average colour where the file holds none, and the estimate then takes that for grey (IMG_3's leaves came out
// blue-grey). `black`: the mosaic's black level in file codes.
AutoWhiteBalanceReport EstimateScenesGrey(const JpegCoefficients& coefficients, const MosaicRestoreOptions& restore,
                                          const LytroMetadata& metadata, double black) {
  MosaicRestoreOptions first = restore;
  first.iterations = std::min(restore.iterations, kWhiteBalanceRestoreIterations);
  AutoWhiteBalanceReport estimate;
  (void)EstimateMosaicWhiteBalance(RestoreJpegMosaic(coefficients, first), metadata.RequireRawFormat().mosaic, black,
                                   CameraColourMatrix(metadata), CameraWhiteBalanceGains(metadata), &estimate);
  return estimate;
}

// The levels of a plain raw image, in file codes: the ones given, else DefaultPlainLevels; lfsp::Error naming the
// file when they are out of range.
PlainLevels ChosenPlainLevels(const std::string& name, int bit_depth, std::uint16_t largest_stored, bool has_camera,
                              const RawFormat& camera, const PlainRawOptions& options) {
  PlainLevels levels = DefaultPlainLevels(bit_depth, largest_stored, has_camera, camera);
  if (options.black || options.white) levels.why = "given levels";
  levels.black = options.black.value_or(levels.black);
  levels.white = options.white.value_or(levels.white);
  const double full_scale = bit_depth == 8 ? 255.0 : 65535.0;
  if (!(levels.black >= 0.0 && levels.white > levels.black && levels.white <= full_scale))
    throw Error(name + ": levels black " + std::to_string(levels.black) + " / white " + std::to_string(levels.white) +
                " out of range for a " + std::to_string(bit_depth) +
                "-bit image (need 0 <= black < white <= " + std::to_string(static_cast<int>(full_scale)) + ")");
  return levels;
}

}  // namespace

std::string_view ToString(JpegGrey grey) { return grey == JpegGrey::kScene ? "scene" : "sensor"; }

JpegGrey JpegGreyFromString(const std::string& name) {
  if (name == "sensor") return JpegGrey::kSensor;
  if (name == "scene") return JpegGrey::kScene;
  throw Error(OptionName("jpeg_grey") + " '" + name + "': unknown (expected sensor or scene)");
}

const CameraFacts& NominalCameraFacts(const std::string& camera, const std::string& source) {
  static const CameraFacts kF01 = {
      "F01",
      BayerPattern::kBGGR,
      12,
      168.0,
      4095.0,
      1.389859962463379e-05,
      1.3999999761581417e-06,
      0.0019290975760668516,
      1.0004994869232178,
      {3.1115827560424805, -1.9393929243087769, -0.172189861536026, -0.3629055917263031, 1.6408803462982178,
       -0.27797481417655945, 0.078967012465000153, -1.1558042764663696, 2.0768373012542725},
      {1.0, 1.1171875, 1.1171875, 1.72265625},
      std::nullopt,
      0.416660010814666748};
  static const CameraFacts kIllum = {
      "ILLUM",
      BayerPattern::kGRBG,
      10,
      64.0,
      1023.0,
      2e-05,
      1.4e-06,
      -0.0008558133849874139,
      1.0003466606140137,
      {2.244826316833496, -0.9087038040161133, -0.33612245321273804, -0.5600823760032654, 1.7229819297790527,
       -0.16289949417114258, -0.5868203043937683, -1.3248286247253418, 2.911648750305176},
      {1.0, 1.0, 1.0, 1.0},
      BayerValues{0.7571942210197449, 1.0, 1.0, 0.7217861413955688},
      std::nullopt};
  const std::string name = Lower(camera);
  if (name == "f01") return kF01;
  if (name == "illum") return kIllum;
  throw Error(source + ": camera '" + camera + "' unknown (expected f01 or illum)");
}

LytroMetadata NominalMetadata(const std::string& camera, int width, int height, const std::string& source) {
  const CameraFacts& facts = NominalCameraFacts(camera, source);
  LytroMetadata metadata;
  metadata.source = source;
  metadata.schema = "nominal " + std::string(facts.model) + " metadata (none in the file)";
  metadata.camera_make = "Lytro, Inc.";
  metadata.camera_model = facts.model;
  RawFormat format;
  format.width = width;
  format.height = height;
  format.black = Uniform(facts.black);
  format.white = Uniform(facts.white);
  format.mosaic = facts.mosaic;
  metadata.raw_format = format;
  MlaDescription mla;
  mla.lens_pitch = facts.lens_pitch;
  mla.pixel_pitch = facts.pixel_pitch;
  mla.rotation = facts.rotation;
  mla.scale_y = facts.scale_y;
  mla.tiling = "hexUniformRowMajor";
  metadata.mla = mla;
  metadata.colour.ccm = facts.ccm;
  metadata.colour.white_balance_gain = facts.white_balance;
  metadata.colour.normalized_response = facts.normalized_response;
  metadata.colour.gamma = facts.gamma;
  return metadata;
}

bool IsPlainRawImagePath(const std::filesystem::path& path) {
  const std::string extension = Extension(path);
  return extension == ".png" || extension == ".tif" || extension == ".tiff" || extension == ".jpg" ||
         extension == ".jpeg";
}

RawInput ReadPlainRawImage(const std::filesystem::path& path, const PlainRawOptions& options) {
  const std::string name = path.string();
  ImageFile image = ReadImage(path);
  if (image.pixels.channels() != 1) {
    // A grey picture saved as RGB (as white images exported by other tools often are) is one channel in disguise.
    std::vector<cv::Mat> planes;
    cv::split(image.pixels, planes);
    for (int c = 1; c < std::min(3, image.pixels.channels()); ++c)
      if (cv::norm(planes[0], planes[static_cast<std::size_t>(c)], cv::NORM_INF) > 0.0)
        throw Error(name + ": a raw Bayer image has one channel; this one has " +
                    std::to_string(image.pixels.channels()) +
                    " different ones (a colour picture is not a raw lenslet "
                    "image)");
    image.pixels = planes[0];
  }
  if (image.bit_depth != 8 && image.bit_depth != 16)
    throw Error(name + ": raw images must be 8- or 16-bit integers; this one has " + std::to_string(image.bit_depth) +
                "-bit samples");
  RawInput input;
  input.path = path;
  input.format = "plain raw image (" + std::to_string(image.bit_depth) + "-bit " +
                 Lower(path.extension().string()).substr(1) + ")";
  const int width = image.pixels.cols, height = image.pixels.rows;
  if (width < 2 || height < 2) throw Error(name + ": image is smaller than one Bayer tile");
  input.has_camera_metadata = !options.camera.empty();
  input.metadata = input.has_camera_metadata ? NominalMetadata(options.camera, width, height, name) : LytroMetadata{};
  if (!input.has_camera_metadata) {
    input.metadata.source = name;
    input.metadata.schema = "none (plain raw image without " + OptionName("camera") + ")";
    input.metadata.raw_format = RawFormat{};
    input.metadata.raw_format->width = width;
    input.metadata.raw_format->height = height;
    input.metadata.mla_problem = "no camera given (" + OptionName("camera") + " f01|illum)";
  }
  RawFormat& format = *input.metadata.raw_format;
  if (options.bayer) format.mosaic = *options.bayer;

  // A greyscale JPEG's mosaic is restored from its coefficients (jpeg_mosaic.h): the plain decode has lost the
  // colour the quantization took. Its codes are fractional, so they are kept at 1/256 of an 8-bit code.
  const double full_scale = image.bit_depth == 8 ? 255.0 : 65535.0;
  double code_scale = 1.0;  // stored raw code per file code
  cv::Mat codes;            // file codes, CV_32FC1
  if (options.jpeg_grey == JpegGrey::kScene && IsJpegPath(path) && !input.has_camera_metadata)
    throw Error(name + ": " + OptionName("jpeg_grey") + " scene needs " + OptionName("camera") +
                " (its colour matrix and white balance)");
  if (IsJpegPath(path) && image.bit_depth == 8 && options.jpeg_restore_iterations > 0) {
    if (const std::optional<JpegCoefficients> coefficients = ReadJpegCoefficients(path)) {
      MosaicRestoreOptions restore;
      restore.iterations = options.jpeg_restore_iterations;
      nlohmann::json grey = "the sensor's: a flat mosaic";
      if (options.jpeg_grey == JpegGrey::kScene) {
        // An 8-bit file's levels do not depend on its codes: the largest stored code does not matter here.
        const double black = ChosenPlainLevels(name, 8, 255, true, format, options).black;
        input.jpeg_scene_grey = EstimateScenesGrey(*coefficients, restore, input.metadata, black);
        restore.grey_gains = BayerPhaseGains(format.mosaic, input.jpeg_scene_grey->gains);
        restore.grey_black = static_cast<float>(black);
        grey = {{"from", "the scene's: the automatic white balance of a short first restoration, on the mosaic"},
                {"gains", input.jpeg_scene_grey->gains},
                {"black", black}};
      }
      MosaicRestoreReport report;
      codes = RestoreJpegMosaic(*coefficients, restore, &report);
      code_scale = 256.0;
      input.jpeg_restoration = {{"iterations", report.iterations},
                                {"mean_change_codes", report.mean_change},
                                {"last_correction", report.last_correction},
                                {"grey", grey}};
    }
  }
  if (IsJpegPath(path)) input.jpeg_block = 8;
  if (codes.empty()) image.pixels.convertTo(codes, CV_32FC1, full_scale);
  image.pixels.release();

  input.raw.width = width;
  input.raw.height = height;
  input.raw.pixels.resize(input.raw.PixelCount());
  std::uint16_t largest = 0;
  for (int y = 0; y < height; ++y) {
    const float* row = codes.ptr<float>(y);
    std::uint16_t* out = input.raw.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    for (int x = 0; x < width; ++x) {
      out[x] = static_cast<std::uint16_t>(
          std::lround(std::clamp(static_cast<double>(row[x]), 0.0, full_scale) * code_scale));
      largest = std::max(largest, out[x]);
    }
  }

  const PlainLevels levels =
      ChosenPlainLevels(name, image.bit_depth, largest, input.has_camera_metadata, format, options);
  format.black = Uniform(levels.black * code_scale);
  format.white = Uniform(levels.white * code_scale);
  input.levels = levels.why + fmt::format(": black {:g}, white {:g}", levels.black, levels.white);
  return input;
}

RawInput OpenRawInput(const std::filesystem::path& path, const PlainRawOptions& options) {
  if (IsPlainRawImagePath(path)) return ReadPlainRawImage(path, options);
  const LytroCapture capture = OpenLytroCapture(path);
  (void)capture.RawBytes();  // "<file>: no raw image: this file holds ..."
  if (!capture.metadata) throw Error(path.string() + ": no frame metadata (" + capture.metadata_problem + ")");
  RawInput input;
  input.path = path;
  input.format = capture.format;
  input.metadata = *capture.metadata;
  const Stopwatch unpack;
  input.raw = capture.ReadRawImage();
  input.unpack_seconds = unpack.Seconds();
  input.white_image = capture.IsWhiteImage();
  input.has_camera_metadata = true;
  input.levels = "the file's metadata";
  return input;
}

}  // namespace lfsp::decode
