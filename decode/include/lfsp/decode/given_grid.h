#pragma once

// A lenslet lattice given rather than fitted (`lfsp decode --grid FILE`): the grid a user already holds, from lfsp
// or from LFToolbox, used as it is instead of fitting one on the white image or the capture.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {

// LFToolbox's LensletGridModel (HSpacing, VSpacing, HOffset, VOffset, Rot, Orientation, FirstPosShiftRow, UMax,
// VMax) as our lattice on a sensor_width x sensor_height sensor. LFToolbox places lens (c, r) (0-based column and
// row of its grid) at (HOffset, VOffset) + R(Rot) ((c + shifted(r) / 2) HSpacing, r VSpacing) in 1-based MATLAB
// pixel coordinates, the rows r = FirstPosShiftRow - 1, FirstPosShiftRow + 1, ... shifted; ours are 0-based, so the
// origin moves by one pixel and FirstPosShiftRow 2 is our row_shift 0. The lenses used are those whose whole
// micro-image lies on the sensor, indexed as a fitted grid is from the same optical axis (axis_x, axis_y: see
// GridGuess), so that a given grid and a fitted one index the same lens alike; UMax and VMax are not needed.
// lfsp::Error naming `source` for a missing or non-numeric field, spacings or rotation out of range, or an
// Orientation other than "horz" (LFToolbox's "vert" is for cameras with vertical lens rows, which no Lytro has).
LensletGrid GridFromLfToolboxModel(const nlohmann::json& model, int sensor_width, int sensor_height, double axis_x,
                                   double axis_y, const std::string& source);

// The lattice in a grid file, for a sensor_width x sensor_height capture whose optical axis is near (axis_x,
// axis_y). Accepted:
//   - lfsp's own grid: what `lfsp grid --out` writes, a decode summary (its "grid"), or the bare object; it must
//     describe a sensor of the same size;
//   - LFToolbox's LensletGridModel, at the top of the file or under "LensletGridModel" (a CalInfo.json, a white
//     image's .grid.json).
// fit_method says where the grid came from. lfsp::Error naming the file if it cannot be read, is not JSON, holds
// neither grid, or holds an lfsp grid of another sensor size.
LensletGrid ReadGivenGrid(const std::filesystem::path& path, int sensor_width, int sensor_height, double axis_x,
                          double axis_y);

// lfsp::Error naming `source` unless `grid` is for a sensor_width x sensor_height sensor and its stored lens range
// has every micro-image on it (slicing would read outside the sensor otherwise): what any stored grid must pass.
void RequireGridOnSensor(const LensletGrid& grid, int sensor_width, int sensor_height, const std::string& source);

}  // namespace lfsp::decode
