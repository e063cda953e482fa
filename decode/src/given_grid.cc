#include "lfsp/decode/given_grid.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "lattice.h"
#include "lfsp/core/error.h"
#include "lfsp/core/json_fields.h"
#include "lfsp/core/untrusted_json.h"
#include "lfsp/decode/lfp_container.h"

namespace lfsp::decode {
namespace {

// A grid file is a few kilobytes; a bigger one is not a grid (and is not read into memory whole).
constexpr std::uintmax_t kMaxGridFileBytes = 16u << 20;

nlohmann::json ParseGridFile(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxGridFileBytes)
    throw Error(path.string() + ": " + std::to_string(size) + " bytes is too large for a lenslet grid file");
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return ParseUntrustedJsonObject(text, path.string());
}

bool IsLfToolboxModel(const nlohmann::json& json) { return json.is_object() && json.contains("HSpacing"); }
bool IsLfspGrid(const nlohmann::json& json) { return json.is_object() && json.contains("spacing_x"); }

}  // namespace

LensletGrid GridFromLfToolboxModel(const nlohmann::json& model, int sensor_width, int sensor_height, double axis_x,
                                   double axis_y, const std::string& source) {
  const JsonSource where(source);
  constexpr std::string_view kPrefix = "LensletGridModel.";
  const std::string orientation = RequireString(model, "Orientation", where, kPrefix);
  if (orientation != "horz")
    throw Error(source + ": LensletGridModel.Orientation '" + orientation +
                "' is not supported (only 'horz': lens rows along the sensor's rows, as in every Lytro camera)");
  HexLattice lattice;
  lattice.spacing_x = RequireNumber(model, "HSpacing", where, kPrefix);
  lattice.spacing_y = RequireNumber(model, "VSpacing", where, kPrefix);
  lattice.rotation = RequireNumber(model, "Rot", where, kPrefix);
  // 1-based MATLAB pixel coordinates to our 0-based pixel centres.
  lattice.origin_x = RequireNumber(model, "HOffset", where, kPrefix) - 1.0;
  lattice.origin_y = RequireNumber(model, "VOffset", where, kPrefix) - 1.0;
  const int first_shifted_row = RequireInt(model, "FirstPosShiftRow", where, kPrefix);
  if (first_shifted_row != 1 && first_shifted_row != 2)
    throw Error(source + ": LensletGridModel.FirstPosShiftRow must be 1 or 2, not " +
                std::to_string(first_shifted_row));
  // LFToolbox shifts its 0-based rows FirstPosShiftRow - 1, +2, ...; ours shifts rows with (j + row_shift) odd.
  lattice.row_shift = first_shifted_row % 2;
  const bool spacings_plausible = lattice.spacing_x > 2.0 && lattice.spacing_y > 2.0 &&
                                  lattice.spacing_x < 0.25 * std::max(sensor_width, sensor_height) &&
                                  std::abs(lattice.spacing_y / lattice.spacing_x - std::sqrt(3.0) / 2.0) < 0.15;
  if (!spacings_plausible || !(std::abs(lattice.rotation) <= 0.5) || !std::isfinite(lattice.origin_x) ||
      !std::isfinite(lattice.origin_y) || std::abs(lattice.origin_x) > 4.0 * sensor_width ||
      std::abs(lattice.origin_y) > 4.0 * sensor_height)
    throw Error(source +
                ": LensletGridModel out of range for this sensor (spacings above 2 px in a hexagonal ratio, "
                "|Rot| <= 0.5 rad, offsets near the sensor)");
  LensletGrid grid;
  try {
    grid = GridFromLattice(lattice, axis_x, axis_y, sensor_width, sensor_height);
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  grid.fit_method = "given: LFToolbox LensletGridModel (" + source + ")";
  return grid;
}

void RequireGridOnSensor(const LensletGrid& grid, int sensor_width, int sensor_height, const std::string& source) {
  if (grid.sensor_width != sensor_width || grid.sensor_height != sensor_height)
    throw Error(source + ": the grid is for a " + std::to_string(grid.sensor_width) + "x" +
                std::to_string(grid.sensor_height) + " sensor, the capture's is " + std::to_string(sensor_width) + "x" +
                std::to_string(sensor_height));
  // A hexagonal lattice's rows are sqrt(3)/2 of its spacing apart (0.8665 on both Lytro cameras), at least 8 lenses
  // fit across the sensor (as a fit needs), and the lenses cover most of it: a grid that lies about its shape would
  // ask the decode for views of any size (issue 15: memory bounded by the real input).
  const double rows_over_spacing = grid.spacing_y / grid.spacing_x;
  if (!(rows_over_spacing > 0.7 && rows_over_spacing < 1.05) ||
      !(grid.spacing_x * 8.0 <= std::min(sensor_width, sensor_height)) ||
      !(grid.columns * grid.spacing_x >= 0.5 * sensor_width && grid.rows * grid.spacing_y >= 0.5 * sensor_height))
    throw Error(source + ": not a lenslet grid of this sensor (spacing " + std::to_string(grid.spacing_x) + " x " +
                std::to_string(grid.spacing_y) + " px, " + std::to_string(grid.columns) + " x " +
                std::to_string(grid.rows) + " lenses: rows must be 0.7-1.05 of the spacing apart, at least 8 lenses " +
                "fit across, and the lenses cover half the sensor each way)");
  // The stored lens range must lie on this sensor, or slicing would read outside it: its end lenses in the first
  // and last two rows (rows alternate in shift; the lattice is straight between them).
  for (const int j : {0, 1, grid.rows - 2, grid.rows - 1})
    for (const int i : {0, grid.columns - 1}) {
      double x = 0.0, y = 0.0;
      grid.Centre(i, j, x, y);
      if (!grid.MicroImageOnSensor(x, y, sensor_width, sensor_height))
        throw Error(source + ": lens (" + std::to_string(i) + ", " + std::to_string(j) +
                    ") of the grid has its micro-image off the sensor");
    }
}

LensletGrid ReadGivenGrid(const std::filesystem::path& path, int sensor_width, int sensor_height, double axis_x,
                          double axis_y) {
  const std::string source = path.string();
  const nlohmann::json document = ParseGridFile(path);
  if (IsLfToolboxModel(document))
    return GridFromLfToolboxModel(document, sensor_width, sensor_height, axis_x, axis_y, source);
  if (document.contains("LensletGridModel") && IsLfToolboxModel(document["LensletGridModel"]))
    return GridFromLfToolboxModel(document["LensletGridModel"], sensor_width, sensor_height, axis_x, axis_y, source);
  const nlohmann::json* ours = IsLfspGrid(document) ? &document : nullptr;
  if (!ours && document.contains("grid") && IsLfspGrid(document["grid"])) ours = &document["grid"];
  if (!ours)
    throw Error(source +
                ": holds no lenslet grid (neither lfsp's 'grid' with spacing_x nor LFToolbox's "
                "LensletGridModel)");
  LensletGrid grid = LensletGrid::FromJson(*ours, source);
  RequireGridOnSensor(grid, sensor_width, sensor_height, source);
  grid.fit_method = "given: lfsp grid (" + source + ")";
  return grid;
}

}  // namespace lfsp::decode
