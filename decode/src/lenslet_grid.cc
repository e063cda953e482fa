#include "lfsp/decode/lenslet_grid.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>

#include "bayer_levels.h"
#include "lattice.h"
#include "lfsp/core/error.h"
#include "lfsp/core/json_fields.h"
#include "lfsp/core/ordered_reduction.h"

namespace lfsp::decode {
namespace {

double RequireNumber(const nlohmann::json& json, const char* key, const std::string& source) {
  if (!json.contains(key) || !json[key].is_number())
    throw Error(source + ": lenslet grid field '" + key + "' missing or not a number");
  return json[key].get<double>();
}

// A count or size: a whole number an int holds.
int RequireCount(const nlohmann::json& json, const char* key, const std::string& source) {
  const std::optional<int> value = WholeInt(RequireNumber(json, key, source));
  if (!value) throw Error(source + ": lenslet grid field '" + key + "' is not a whole number an int holds");
  return *value;
}

// One row of LensLabels: the nearest lens of each pixel (NearestLensAt), the lattice coordinates stepped along the row.
// Built twice (AVX2 and generic) and chosen at run time: with SSE4.1 and later, floor and nearbyint are single
// instructions instead of library calls, which were most of the time.
__attribute__((target_clones("avx2", "default"))) void LensLabelsRow(const LensletGrid& grid, double along,
                                                                     double across, double along_step,
                                                                     double across_step, std::uint8_t* row,
                                                                     int columns) {
  for (int x = 0; x < columns; ++x, along += along_step, across += across_step) {
    const NearestLens nearest = NearestLensAt(grid, along, across);
    row[x] = static_cast<std::uint8_t>((nearest.i & 3) + 4 * (nearest.j & 1));
  }
}

}  // namespace

cv::Mat LensLabels(const LensletGrid& grid) {
  cv::Mat labels(grid.sensor_height, grid.sensor_width, CV_8U);
  const double c = std::cos(grid.rotation), s = std::sin(grid.rotation);
  const double along_step = c / grid.spacing_x, across_step = -s / grid.spacing_y;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < labels.rows; ++y) {
    const double dy = y - grid.origin_y, dx0 = -grid.origin_x;
    LensLabelsRow(grid, (c * dx0 + s * dy) / grid.spacing_x, (-s * dx0 + c * dy) / grid.spacing_y, along_step,
                  across_step, labels.ptr<std::uint8_t>(y), labels.cols);
  }
  return labels;
}

nlohmann::json LensletGrid::ToJson() const {
  return {{"spacing_x", spacing_x},
          {"spacing_y", spacing_y},
          {"rotation", rotation},
          {"origin_x", origin_x},
          {"origin_y", origin_y},
          {"row_shift", row_shift},
          {"columns", columns},
          {"rows", rows},
          {"sensor_width", sensor_width},
          {"sensor_height", sensor_height},
          {"rms_residual", rms_residual},
          {"lenses_measured", lenses_measured},
          {"lenses_used", lenses_used},
          {"fit_method", fit_method},
          {"blocks", blocks},
          {"blocks_used", blocks_used}};
}

LensletGrid LensletGrid::FromJson(const nlohmann::json& json, const std::string& source) {
  if (!json.is_object()) throw Error(source + ": lenslet grid is not a JSON object");
  LensletGrid grid;
  grid.spacing_x = RequireNumber(json, "spacing_x", source);
  grid.spacing_y = RequireNumber(json, "spacing_y", source);
  grid.rotation = RequireNumber(json, "rotation", source);
  grid.origin_x = RequireNumber(json, "origin_x", source);
  grid.origin_y = RequireNumber(json, "origin_y", source);
  grid.row_shift = RequireCount(json, "row_shift", source);
  grid.columns = RequireCount(json, "columns", source);
  grid.rows = RequireCount(json, "rows", source);
  grid.sensor_width = RequireCount(json, "sensor_width", source);
  grid.sensor_height = RequireCount(json, "sensor_height", source);
  // The fit statistics are optional, but present ones must have their type (an lfsp::Error, not a JSON exception).
  const JsonSource where(source);
  grid.rms_residual = NumberAt(json, "rms_residual", where).value_or(0.0);
  grid.lenses_measured = IntAt(json, "lenses_measured", where).value_or(0);
  grid.lenses_used = IntAt(json, "lenses_used", where).value_or(0);
  grid.fit_method = StringAt(json, "fit_method", where).value_or("");
  grid.blocks = IntAt(json, "blocks", where).value_or(0);
  grid.blocks_used = IntAt(json, "blocks_used", where).value_or(0);
  if (!(grid.spacing_x > 2.0 && grid.spacing_y > 2.0) || grid.columns < 2 || grid.rows < 2 || grid.sensor_width <= 0 ||
      grid.sensor_height <= 0 || std::abs(grid.rotation) > 0.5)
    throw Error(source + ": lenslet grid out of range (spacing > 2 px, at least 2x2 lenses, |rotation| <= 0.5)");
  return grid;
}

GridGuess GuessFromMetadata(const LytroMetadata& metadata, int sensor_width, int sensor_height) {
  const MlaDescription& mla = metadata.RequireMla();
  if (!(mla.lens_pitch > 0.0 && mla.pixel_pitch > 0.0))
    throw Error(metadata.source + ": devices.mla.lensPitch and devices.sensor.pixelPitch must be positive");
  GridGuess guess;
  guess.spacing = mla.ApproxSpacingPixels() * (mla.scale_x > 0.0 ? mla.scale_x : 1.0);
  guess.scale_y = mla.scale_y > 0.0 ? mla.scale_y : 1.0;
  guess.rotation = mla.rotation;
  guess.axis_x = 0.5 * (sensor_width - 1) - mla.offset_x / mla.pixel_pitch;
  guess.axis_y = 0.5 * (sensor_height - 1) - mla.offset_y / mla.pixel_pitch;
  return guess;
}

cv::Mat WhiteImageToGrey(const RawImage& white, const RawFormat& format, const std::string& source) {
  if (white.width < 2 || white.height < 2 || white.pixels.size() != white.PixelCount())
    throw Error(source + ": white image has no pixels or a buffer of the wrong size");
  const PhaseLevels levels = LevelsOf(format, source);
  cv::Mat grey(white.height, white.width, CV_32F);
  // Levels, and the mean of each Bayer phase (the sensor's colour response to the white diffuser), summed in a fixed
  // order so that the gains do not depend on the thread count (docs/DESIGN.md, "Same input, same bytes").
  using PhaseSums = std::array<double, 4>;
  const PhaseSums sums = OrderedParallelSum(
      white.height, [] { return PhaseSums{}; },
      [&](int y, PhaseSums& local) {
        const std::uint16_t* in = white.pixels.data() + static_cast<std::size_t>(y) * white.width;
        float* out = grey.ptr<float>(y);
        for (int x = 0; x < white.width; ++x) {
          const int phase = 2 * (y & 1) + (x & 1);
          const float value = std::max(0.0f, (static_cast<float>(in[x]) - levels.black[phase]) * levels.scale[phase]);
          out[x] = value;
          local[phase] += value;
        }
      },
      [](PhaseSums& into, const PhaseSums& from) {
        for (int phase = 0; phase < 4; ++phase) into[phase] += from[phase];
      });
  std::array<float, 4> gain{};
  const double mean_all = (sums[0] + sums[1] + sums[2] + sums[3]) / 4.0;
  for (int phase = 0; phase < 4; ++phase) {
    if (!(sums[phase] > 0.0)) throw Error(source + ": white image is black in one Bayer channel");
    gain[phase] = static_cast<float>(mean_all / sums[phase]);
  }
  // Histogram of the balanced values for the 99.9th percentile.
  constexpr int kBins = 4096;
  std::vector<long long> histogram(kBins, 0);
  // Levels map to [0, 1] (a little above for pixels past the white level), so balanced values stay below this.
  const float top = 1.1f * *std::max_element(gain.begin(), gain.end());
#pragma omp parallel
  {
    std::vector<long long> local(kBins, 0);
#pragma omp for schedule(static)
    for (int y = 0; y < white.height; ++y) {
      float* row = grey.ptr<float>(y);
      for (int x = 0; x < white.width; ++x) {
        row[x] *= gain[2 * (y & 1) + (x & 1)];
        ++local[std::min(kBins - 1, static_cast<int>(row[x] / top * kBins))];
      }
    }
#pragma omp critical
    for (int b = 0; b < kBins; ++b) histogram[b] += local[b];
  }
  const long long wanted = static_cast<long long>(0.999 * static_cast<double>(white.PixelCount()));
  long long count = 0;
  int bin = 0;
  while (bin < kBins - 1 && count + histogram[bin] < wanted) count += histogram[bin++];
  const double percentile = (bin + 1.0) * top / kBins;
  if (!(percentile > 0.0)) throw Error(source + ": white image is black");
  grey *= 1.0 / percentile;
  return grey;
}

}  // namespace lfsp::decode
