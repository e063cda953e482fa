#include "lfsp/decode/lenslet_decoder.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/core.hpp>

#include "bayer_preprocess.h"
#include "lenslet_slicing.h"
#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

class StepTimer {
 public:
  explicit StepTimer(DecodeReport& report) : report_(report), start_(std::chrono::steady_clock::now()) {}
  void Lap(const std::string& step) {
    const auto now = std::chrono::steady_clock::now();
    report_.seconds[step] = std::chrono::duration<double>(now - start_).count();
    start_ = now;
  }

 private:
  DecodeReport& report_;
  std::chrono::steady_clock::time_point start_;
};

void CheckSize(const RawImage& image, int width, int height, const std::string& what) {
  if (image.width != width || image.height != height || image.pixels.size() != image.PixelCount())
    throw Error(what + ": raw image is " + std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                std::to_string(image.pixels.size()) + " pixels; the lenslet grid expects " + std::to_string(width) +
                "x" + std::to_string(height));
}

// Per-phase factors applied to the white image before dividing by it. Linear: none, so the sensor's colour response
// cancels. Camera: the inverse sensor response (normalizedResponses, or the white image's own channel means), so
// the capture keeps its raw colour and the camera's white balance applies afterwards.
std::array<float, 4> WhiteGains(ColourMode mode, const RawImage& white, const LytroMetadata& white_metadata,
                                const PhaseLevels& levels, BayerPattern pattern) {
  std::array<float, 4> gains = {1.0f, 1.0f, 1.0f, 1.0f};
  if (mode == ColourMode::kLinear) return gains;
  const std::array<int, 4> tile = TileChannels(pattern);
  if (const auto& response = white_metadata.colour.normalized_response;
      response && response->r > 0 && response->gr > 0 && response->gb > 0 && response->b > 0) {
    for (int phase = 0; phase < 4; ++phase)
      gains[static_cast<std::size_t>(phase)] =
          static_cast<float>(response->gr / Channel(*response, tile[static_cast<std::size_t>(phase)]));
    return gains;
  }
  std::array<double, 4> sums{};
  for (int y = 0; y < white.height; y += 3)
    for (int x = 0; x < white.width; ++x) {
      const int phase = BayerPhase(x, y);
      sums[static_cast<std::size_t>(phase)] += (white.at(y, x) - levels.black[static_cast<std::size_t>(phase)]) *
                                               levels.scale[static_cast<std::size_t>(phase)];
    }
  const double green = 0.5 * (sums[static_cast<std::size_t>(std::find(tile.begin(), tile.end(), 1) - tile.begin())] +
                              sums[static_cast<std::size_t>(std::find(tile.begin(), tile.end(), 2) - tile.begin())]);
  for (int phase = 0; phase < 4; ++phase)
    if (sums[static_cast<std::size_t>(phase)] > 0)
      gains[static_cast<std::size_t>(phase)] = static_cast<float>(green / sums[static_cast<std::size_t>(phase)]);
  return gains;
}

// The camera's colour transform as one 3x3 matrix: exposure bias * CCM * diag(white balance).
std::array<float, 9> CameraColourMatrix(const LytroMetadata& metadata) {
  std::array<double, 3> balance = {1.0, 1.0, 1.0};
  if (const auto& gain = metadata.colour.white_balance_gain; gain && gain->gr > 0 && gain->gb > 0)
    balance = {gain->r / (0.5 * (gain->gr + gain->gb)), 1.0, gain->b / (0.5 * (gain->gr + gain->gb))};
  std::array<double, 9> ccm = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (metadata.colour.ccm) ccm = *metadata.colour.ccm;
  const double bias = std::exp2(metadata.modulation_exposure_bias.value_or(0.0));
  std::array<float, 9> matrix{};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      matrix[static_cast<std::size_t>(3 * row + col)] = static_cast<float>(
          bias * ccm[static_cast<std::size_t>(3 * row + col)] * balance[static_cast<std::size_t>(col)]);
  return matrix;
}

// sRGB encoding through a table (the curve is smooth; 4096 linear segments are exact to ~1e-5).
class SrgbTable {
 public:
  SrgbTable() {
    for (int k = 0; k <= kSize; ++k) {
      const double linear = static_cast<double>(k) / kSize;
      table_[static_cast<std::size_t>(k)] =
          static_cast<float>(linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055);
    }
  }
  float operator()(float linear) const {
    const float position = std::clamp(linear, 0.0f, 1.0f) * kSize;
    const int k = std::min(kSize - 1, static_cast<int>(position));
    const float f = position - static_cast<float>(k);
    return table_[static_cast<std::size_t>(k)] +
           f * (table_[static_cast<std::size_t>(k) + 1] - table_[static_cast<std::size_t>(k)]);
  }

 private:
  static constexpr int kSize = 4096;
  std::array<float, kSize + 1> table_{};
};

// Applies the colour matrix (camera mode), scales so the brightest well-lit ray is at most 1 (no highlight is
// clipped: the whole light field is darkened instead), clamps the rest (unlit rays between micro-images) and encodes.
double FinishColour(LightField& light_field, ColourMode mode, const std::array<float, 9>& matrix) {
  float* data = light_field.data();
  const float* weights = light_field.weights().data();
  const std::size_t rays = light_field.weights().size();
  float brightest = 0.0f;
#pragma omp parallel for schedule(static) reduction(max : brightest)
  for (std::size_t k = 0; k < rays; ++k) {
    float* p = data + 3 * k;
    if (mode == ColourMode::kCamera) {
      const float r = p[0], g = p[1], b = p[2];
      p[0] = std::max(0.0f, matrix[0] * r + matrix[1] * g + matrix[2] * b);
      p[1] = std::max(0.0f, matrix[3] * r + matrix[4] * g + matrix[5] * b);
      p[2] = std::max(0.0f, matrix[6] * r + matrix[7] * g + matrix[8] * b);
    }
    if (weights[k] >= 0.5f) brightest = std::max({brightest, p[0], p[1], p[2]});
  }
  const double scale = brightest > 1.0f ? 1.0 / brightest : 1.0;
  const auto scale_f = static_cast<float>(scale);
  static const SrgbTable srgb;
  float* weights_out = light_field.weights().data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < rays; ++k) {
    float* p = data + 3 * k;
    for (int c = 0; c < 3; ++c) {
      const float value = std::min(1.0f, p[c] * scale_f);
      p[c] = mode == ColourMode::kCamera ? srgb(value) : value;
    }
    weights_out[k] = std::clamp(weights_out[k], 0.0f, 1.0f);
  }
  return scale;
}

}  // namespace

std::string_view ToString(ColourMode mode) { return mode == ColourMode::kLinear ? "linear" : "camera"; }

ColourMode ColourModeFromString(const std::string& name) {
  if (name == "linear") return ColourMode::kLinear;
  if (name == "camera") return ColourMode::kCamera;
  throw Error("colour mode '" + name + "': unknown (expected linear or camera)");
}

DecodedGeometry DecodedGeometryFor(const LensletGrid& grid) {
  if (!(grid.spacing_x > 2.0) || grid.columns < 2 || grid.rows < 2)
    throw Error("lenslet grid: spacing and size out of range for decoding");
  DecodedGeometry geometry;
  int n = static_cast<int>(std::ceil(grid.spacing_x));
  if (n % 2 == 1) ++n;
  geometry.views = n - 1;
  geometry.view_step = grid.spacing_x / n;
  geometry.width = static_cast<int>(std::floor((grid.columns - 1) / 0.86602540378443864676)) + 1;
  geometry.height = grid.rows;
  return geometry;
}

nlohmann::json DecodeReport::ToJson() const {
  return {{"demosaic", demosaic},
          {"colour", colour},
          {"hot_pixels_corrected", hot_pixels_corrected},
          {"output_scale", output_scale},
          {"seconds", seconds}};
}

LightField DecodeLenslet(const RawImage& capture, const LytroMetadata& capture_metadata, const RawImage& white,
                         const LytroMetadata& white_metadata, const LensletGrid& grid, const DecodeOptions& options,
                         DecodeReport* report) {
  DecodeReport local_report;
  DecodeReport& out_report = report ? *report : local_report;
  out_report = {};
  out_report.demosaic = std::string(ToString(options.demosaic));
  out_report.colour = std::string(ToString(options.colour));
  StepTimer timer(out_report);
  CheckSize(capture, grid.sensor_width, grid.sensor_height, capture_metadata.source);
  CheckSize(white, grid.sensor_width, grid.sensor_height, white_metadata.source);
  const RawFormat& capture_format = capture_metadata.RequireRawFormat();
  const RawFormat& white_format = white_metadata.RequireRawFormat();
  if (capture_format.mosaic != white_format.mosaic)
    throw Error(white_metadata.source + ": Bayer pattern " + std::string(ToString(white_format.mosaic)) +
                " differs from the capture's " + std::string(ToString(capture_format.mosaic)));
  const DecodedGeometry geometry = DecodedGeometryFor(grid);

  // 1. Levels, hot pixels, devignetting (Bayer domain).
  const PhaseLevels capture_levels = LevelsOf(capture_format, capture_metadata.source);
  const PhaseLevels white_levels = LevelsOf(white_format, white_metadata.source);
  cv::Mat bayer = ApplyLevels(capture, capture_levels);
  timer.Lap("levels");
  if (options.correct_hot_pixels)
    out_report.hot_pixels_corrected = CorrectHotPixels(bayer, static_cast<float>(options.hot_pixel_margin));
  timer.Lap("hot_pixels");
  const std::array<float, 4> white_gains =
      WhiteGains(options.colour, white, white_metadata, white_levels, white_format.mosaic);
  Devignette(bayer, white, white_levels, white_gains, static_cast<float>(options.min_white), white_metadata.source);
  const cv::Mat grey_white = WhiteImageToGrey(white, white_format, white_metadata.source);
  timer.Lap("devignette");

  // 2. Demosaic.
  const cv::Mat rgb = Demosaic(bayer, capture_format.mosaic, options.demosaic);
  bayer.release();
  timer.Lap("demosaic");

  // 3. One interpolation pass into the 4D grid.
  LightFieldShape shape;
  shape.nu = shape.nv = geometry.views;
  shape.width = geometry.width;
  shape.height = geometry.height;
  shape.channels = 3;
  LightField light_field(shape);
  light_field.EnableWeights(0.0f);
  timer.Lap("allocate");
  SliceLensletImage(rgb, grey_white, grid, geometry, light_field);
  SoftenRowAlternation(light_field, static_cast<float>(options.dehex));
  timer.Lap("slice");

  // 4. Colour.
  const std::array<float, 9> matrix = CameraColourMatrix(capture_metadata);
  out_report.output_scale = FinishColour(light_field, options.colour, matrix);
  light_field.transfer = options.colour == ColourMode::kCamera ? Transfer::kSrgb : Transfer::kLinear;
  timer.Lap("colour");

  light_field.metadata["decode"] = {
      {"source", capture_metadata.source},       {"white_image", white_metadata.source},
      {"demosaic", out_report.demosaic},         {"colour", out_report.colour},
      {"output_scale", out_report.output_scale}, {"hot_pixels_corrected", out_report.hot_pixels_corrected},
      {"view_step_pixels", geometry.view_step},  {"grid_spacing_x", grid.spacing_x},
      {"grid_spacing_y", grid.spacing_y},        {"grid_rotation", grid.rotation},
      {"grid_rms_residual", grid.rms_residual}};
  if (!capture_metadata.camera_model.empty())
    light_field.metadata["decode"]["camera_model"] = capture_metadata.camera_model;
  return light_field;
}

}  // namespace lfsp::decode
