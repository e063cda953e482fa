#include "lfsp/decode/lenslet_decoder.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "bayer_preprocess.h"
#include "highlights.h"
#include "lenslet_slicing.h"
#include "lfsp/core/error.h"
#include "lfsp/core/memory_usage.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/decode/lattice_gain.h"
#include "lfsp/decode/lattice_pattern.h"
#include "lfsp/decode/view_quality.h"
#include "lfsp/decode/white_balance.h"

namespace lfsp::decode {
namespace {

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

// The colour transform of a mode as one 3x3 matrix applied to devignetted sensor RGB.
//   camera: exposure bias * CCM * diag(white balance): the white image kept the sensor's raw colour, so the
//           white balance applies, then the colour matrix.
//   linear: CCM alone: dividing by the white image has already balanced the channels (to the calibration light),
//           so only the colour matrix takes sensor primaries to scene-linear (sRGB-primary) RGB.
std::array<float, 9> ColourMatrix(const LytroMetadata& metadata, ColourMode mode,
                                  const std::array<double, 3>& balance) {
  const std::array<double, 9> ccm = CameraColourMatrix(metadata);
  // LFToolbox v0.6: the F01's bias is stated one stop lower than it is applied (bias + 1); the Illum's as is.
  const double stops = metadata.modulation_exposure_bias.value_or(0.0) + (metadata.camera_model == "F01" ? 1.0 : 0.0);
  const double bias = mode == ColourMode::kCamera ? std::exp2(stops) : 1.0;
  std::array<float, 9> matrix{};
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      matrix[static_cast<std::size_t>(3 * row + col)] = static_cast<float>(
          bias * ccm[static_cast<std::size_t>(3 * row + col)] * balance[static_cast<std::size_t>(col)]);
  return matrix;
}

// The white-balance gains (R, G, B) the colour matrix applies, and their description for the report. Linear
// decodes have none: the white image balanced the channels.
std::array<double, 3> ResolveWhiteBalance(const DecodeOptions& options, const LytroMetadata& metadata,
                                          const cv::Mat& rgb, const cv::Mat& grey_white, nlohmann::json& report) {
  if (options.colour == ColourMode::kLinear) {
    report = {{"mode", "none (linear colour: the white image balances the channels)"}, {"gains", {1.0, 1.0, 1.0}}};
    return {1.0, 1.0, 1.0};
  }
  const WhiteBalance balance = options.white_balance.value_or(WhiteBalance{});
  std::array<double, 3> gains = {1.0, 1.0, 1.0};
  report = {{"mode", ToString(balance)}};
  switch (balance.mode) {
    case WhiteBalanceMode::kCamera:
      gains = CameraWhiteBalanceGains(metadata);
      break;
    case WhiteBalanceMode::kNone:
      break;
    case WhiteBalanceMode::kGains:
      gains = balance.gains;
      break;
    case WhiteBalanceMode::kAuto: {
      if (options.estimated_white_balance) {
        gains = options.estimated_white_balance->gains;
        report["auto"] = options.estimated_white_balance->ToJson();
        report["auto"]["from"] = "the JPEG restoration's estimate on the mosaic";
        break;
      }
      AutoWhiteBalanceReport automatic;
      gains = EstimateWhiteBalance(rgb, grey_white, CameraColourMatrix(metadata), CameraWhiteBalanceGains(metadata),
                                   &automatic);
      report["auto"] = automatic.ToJson();
      break;
    }
  }
  report["gains"] = gains;
  return gains;
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

namespace {

// The summary's and the metadata's "lattice_gain": rms and largest deviation over the views measured, or null when
// the step did not run.
nlohmann::json LatticeGainJson(const std::optional<LatticeGainReport>& report) {
  if (!report) return nullptr;
  return {{"rms", report->rms}, {"max", report->max}, {"views", report->views}};
}

// The same for "jpeg_block_gain".
nlohmann::json JpegBlockGainJson(const std::optional<JpegBlockGainReport>& report) {
  if (!report) return nullptr;
  return {{"rms", report->rms}, {"max", report->max}, {"views", report->views}};
}

}  // namespace

nlohmann::json DecodeReport::ToJson() const {
  return {{"demosaic", demosaic},
          {"colour", colour},
          {"white_balance", white_balance},
          {"hot_pixels_corrected", hot_pixels_corrected},
          {"clipped_samples", clipped_samples},
          {"highlights_neutralised", highlights_neutralised},
          {"output_scale", output_scale},
          {"row_alternation", row_alternation},
          {"centre_bands", {{"chroma", centre_bands[0]}, {"luma", centre_bands[1]}}},
          {"lattice_gain", LatticeGainJson(lattice_gain)},
          {"jpeg_block_gain", JpegBlockGainJson(jpeg_block_gain)},
          {"seconds", seconds},
          {"cpu_seconds", cpu_seconds},
          {"resident_mb", resident_mb},
          {"peak_resident_mb", peak_resident_mb}};
}

PreparedWhite PrepareWhite(const RawImage& white, const LytroMetadata& white_metadata, ColourMode colour,
                           double min_white) {
  if (!(min_white > 0.0 && min_white < 1.0)) throw Error("min_white must be in (0, 1)");
  PreparedWhite prepared;
  prepared.source = white_metadata.source;
  prepared.format = white_metadata.RequireRawFormat();
  prepared.colour = colour;
  if (white.width != prepared.format.width || white.height != prepared.format.height ||
      white.pixels.size() != white.PixelCount())
    throw Error(white_metadata.source + ": raw image is " + std::to_string(white.width) + "x" +
                std::to_string(white.height) + " but the metadata says " + std::to_string(prepared.format.width) + "x" +
                std::to_string(prepared.format.height));
  const PhaseLevels levels = LevelsOf(prepared.format, prepared.source);
  const std::array<float, 4> gains = WhiteGains(colour, white, white_metadata, levels, prepared.format.mosaic);
  prepared.inverse = InverseWhite(white, levels, gains, static_cast<float>(min_white), prepared.source);
  prepared.grey = WhiteImageToGrey(white, prepared.format, prepared.source);
  return prepared;
}

LightField DecodeLenslet(const RawImage& capture, const LytroMetadata& capture_metadata, const RawImage& white,
                         const LytroMetadata& white_metadata, const LensletGrid& grid, const DecodeOptions& options,
                         DecodeReport* report) {
  CheckSize(white, grid.sensor_width, grid.sensor_height, white_metadata.source);
  const Stopwatch stopwatch;
  const PreparedWhite prepared = PrepareWhite(white, white_metadata, options.colour, options.min_white);
  const double prepare_seconds = stopwatch.Seconds();
  LightField light_field = DecodeLenslet(capture, capture_metadata, prepared, grid, options, report);
  if (report) report->seconds["prepare_white"] = prepare_seconds;
  return light_field;
}

namespace {

// The shape of the decoded light field: the central views of the grid that DecodeOptions::central_views asks for.
LightFieldShape DecodedShape(int requested, const cv::Mat& grey_white, const LensletGrid& grid,
                             const DecodedGeometry& geometry) {
  LightFieldShape all;
  all.nu = all.nv = geometry.views;
  all.width = geometry.width;
  all.height = geometry.height;
  all.channels = 3;
  if (requested < 0) return all;
  if (requested > 0) return CentralShape(all, requested);  // lfsp::Error when it cannot be taken
  const std::vector<double> means = ApproximateViewMeanWeights(grey_white, grid, geometry);
  const int n = WellLitCentralSize(
      all, [&](ViewIndex view) { return means[static_cast<std::size_t>(view.v * geometry.views + view.u)]; },
      kWellLitWeight - kDecodeChoiceMargin);
  return CentralShape(all, n);
}

// The caller's buffers that the decode may free as soon as it is done with them: both when they were handed over
// (the consuming DecodeLenslet), neither otherwise. They are the same objects as the decode's `capture` and `white`,
// which are not read after the point where they are freed.
struct Consumable {
  RawImage* capture = nullptr;
  PreparedWhite* white = nullptr;
};

LightField DecodeFromSensor(const RawImage& capture, const LytroMetadata& capture_metadata, const PreparedWhite& white,
                            const LensletGrid& grid, const DecodeOptions& options, DecodeReport* report,
                            Consumable consumable) {
  DecodeReport local_report;
  DecodeReport& out_report = report ? *report : local_report;
  out_report = {};
  out_report.demosaic = std::string(ToString(options.demosaic));
  out_report.colour = std::string(ToString(options.colour));
  // Wall and CPU seconds of each step into the report (the CPU time shows how well a step uses the cores), and the
  // memory the process holds after it (where the peak comes from).
  Stopwatch stopwatch;
  const auto lap = [&](const char* step) {
    out_report.seconds[step] = stopwatch.Lap(&out_report.cpu_seconds[step]);
    out_report.resident_mb[step] = ResidentMegabytes();
    out_report.peak_resident_mb[step] = PeakResidentMegabytes();
  };
  CheckSize(capture, grid.sensor_width, grid.sensor_height, capture_metadata.source);
  if (white.inverse.cols != grid.sensor_width || white.inverse.rows != grid.sensor_height ||
      white.grey.size() != white.inverse.size())
    throw Error(white.source + ": white image is " + std::to_string(white.inverse.cols) + "x" +
                std::to_string(white.inverse.rows) + ", the lenslet grid's sensor " +
                std::to_string(grid.sensor_width) + "x" + std::to_string(grid.sensor_height));
  if (white.colour != options.colour) throw Error(white.source + ": white image was prepared for another colour mode");
  const RawFormat& capture_format = capture_metadata.RequireRawFormat();
  if (capture_format.mosaic != white.format.mosaic)
    throw Error(white.source + ": Bayer pattern " + std::string(ToString(white.format.mosaic)) +
                " differs from the capture's " + std::string(ToString(capture_format.mosaic)));
  const DecodedGeometry geometry = DecodedGeometryFor(grid);
  const LightFieldShape shape = DecodedShape(options.central_views, white.grey, grid, geometry);

  // 1. Levels, hot pixels and devignetting, in one pass over the Bayer image.
  const PhaseLevels capture_levels = LevelsOf(capture_format, capture_metadata.source);
  cv::Mat bayer = LevelAndDevignette(capture, capture_levels, white.inverse,
                                     options.correct_hot_pixels ? static_cast<float>(options.hot_pixel_margin) : 0.0f,
                                     out_report.hot_pixels_corrected, out_report.clipped_samples);
  if (consumable.capture) *consumable.capture = RawImage{};
  // Without clipped samples the highlights step does not run, and nothing reads the white image's inverse again.
  if (consumable.white && out_report.clipped_samples == 0) consumable.white->inverse.release();
  // What the steps before the decode freed (the white database's reads, the grid fit's images) goes back first.
  ReturnFreedMemory();
  lap("levels_hot_pixels_devignette");

  // 2. Demosaic.
  const cv::Mat lens_labels = LensLabels(grid);
  const MicroImages micro_images{white.grey, lens_labels};
  cv::Mat rgb = Demosaic(bayer, capture_format.mosaic, options.demosaic, 4.0f, &micro_images);
  bayer.release();
  // The Bayer image and the demosaic's own buffers are free: their pages go back before the light field fills up.
  ReturnFreedMemory();
  lap("demosaic");

  // 3. The colour transform and the scale that keeps the brightest well-lit ray at or below 1 (the decode clips no
  //    highlight: the whole light field is darkened instead). What the sensor clipped has lost its colour and is
  //    made neutral first (highlights.h).
  RayColour colour;
  const std::array<double, 3> balance =
      ResolveWhiteBalance(options, capture_metadata, rgb, white.grey, out_report.white_balance);
  if (out_report.clipped_samples > 0)
    out_report.highlights_neutralised = NeutraliseClippedHighlights(
        rgb, white.inverse, capture_format.mosaic, options.demosaic, micro_images, balance, kClippedLevel);
  // The white image's inverse is not read from here on: beside the demosaicked image and the light field it made
  // the decode's peak (an Illum's 166 MB, issue 46). Without clipped samples it went after the levelling.
  if (consumable.white) consumable.white->inverse.release();
  colour.matrix = ColourMatrix(capture_metadata, options.colour, balance);
  const float brightest = BrightestWellLit(rgb, white.grey, colour.matrix);
  colour.scale = brightest > 1.0f ? 1.0f / brightest : 1.0f;
  out_report.output_scale = colour.scale;
  lap("exposure");

  // 4. One interpolation pass into the 4D grid, then the row-alternation softening and encoding.
  // The output (0.35 GB for an Illum's 9x9 views, 1 GB for all 15x15) is left unfilled: the slicing sets every
  // sample and weight, so its pages are first touched there, by both cores, instead of by a serial zero fill. Not
  // before the demosaic: beside its sensor-size buffers the light field made the decode's peak (issue 46).
  LightField light_field(shape, LightField::Unfilled{});
  light_field.EnableWeights(LightField::Unfilled{});
  // The slicing is the last to read the demosaicked image (and, when it was handed over, the white image's grey
  // version): their rows go back as it passes them, so the light field fills up while they empty.
  std::vector<cv::Mat*> read_last = {&rgb};
  if (consumable.white) read_last.push_back(&consumable.white->grey);
  SliceLensletImage(rgb, white.grey, lens_labels, grid, geometry, colour, light_field, read_last);
  rgb.release();
  if (consumable.white) consumable.white->grey.release();
  ReturnFreedMemory();
  lap("slice");
  // The JPEG's block gain first: the lattice gain is measured against a blur across 2 rows, which the block
  // pattern's slow drift would pass into it.
  if (options.flatten_jpeg_blocks && options.jpeg_block > 0) {
    out_report.jpeg_block_gain = FlattenJpegBlockGain(light_field, grid, geometry.view_step, options.jpeg_block);
    lap("flatten_jpeg_blocks");
  }
  if (options.flatten_lattice) {
    out_report.lattice_gain = FlattenLatticeGain(light_field, grid);
    lap("flatten_lattice");
  }
  SoftenAndEncode(light_field, static_cast<float>(options.dehex), options.colour == ColourMode::kCamera);
  light_field.transfer = options.colour == ColourMode::kCamera ? Transfer::kSrgb : Transfer::kLinear;
  lap("soften_encode");
  out_report.row_alternation = RowAlternationRatio(light_field);
  const ViewIndex centre = light_field.shape().Centre();
  out_report.centre_bands = {ChromaBandRatio(light_field, centre), LumaBandRatio(light_field, centre)};
  lap("view_quality");

  light_field.metadata["decode"] = {{"source", capture_metadata.source},
                                    {"white_image", white.source},
                                    {"demosaic", out_report.demosaic},
                                    {"colour", out_report.colour},
                                    {"white_balance", out_report.white_balance},
                                    {"output_scale", out_report.output_scale},
                                    {"hot_pixels_corrected", out_report.hot_pixels_corrected},
                                    {"highlights_neutralised", out_report.highlights_neutralised},
                                    {"view_step_pixels", geometry.view_step},
                                    {"views_of_grid", geometry.views},
                                    {"grid_spacing_x", grid.spacing_x},
                                    {"grid_spacing_y", grid.spacing_y},
                                    {"grid_rotation", grid.rotation},
                                    {"grid_rms_residual", grid.rms_residual},
                                    {"row_alternation", out_report.row_alternation},
                                    {"lattice_gain", LatticeGainJson(out_report.lattice_gain)},
                                    {"jpeg_block_gain", JpegBlockGainJson(out_report.jpeg_block_gain)}};
  if (!capture_metadata.camera_model.empty())
    light_field.metadata["decode"]["camera_model"] = capture_metadata.camera_model;
  return light_field;
}

}  // namespace

LightField DecodeLenslet(const RawImage& capture, const LytroMetadata& capture_metadata, const PreparedWhite& white,
                         const LensletGrid& grid, const DecodeOptions& options, DecodeReport* report) {
  return DecodeFromSensor(capture, capture_metadata, white, grid, options, report, Consumable{});
}

LightField DecodeLenslet(RawImage&& capture, const LytroMetadata& capture_metadata, PreparedWhite&& white,
                         const LensletGrid& grid, const DecodeOptions& options, DecodeReport* report) {
  return DecodeFromSensor(capture, capture_metadata, white, grid, options, report, Consumable{&capture, &white});
}

}  // namespace lfsp::decode
