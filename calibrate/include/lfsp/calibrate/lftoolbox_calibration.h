#pragma once

// LFToolbox's calibration file (CalInfo.json, written by LFUtilCalLensletCam / LFCalRefine) read as ours, so that a
// MATLAB user's calibration rectifies the light fields LFToolbox decoded for it (`lfsp rectify IMG__Decoded.mat
// --calibration CalInfo.json`).
//
// Both use the same ray model (ray_model.h), but index a sample differently. LFToolbox's n = (i, j, k, l, 1) is
// 1-based with i, j the view column and row and k, l the pixel column and row; ours is 0-based with the pixel first.
// So our H is LFToolbox's EstCamIntrinsicsH times the permutation-and-shift that takes our index to theirs:
//   n_LFToolbox = (k + 1, l + 1, i + 1, j + 1, 1) for our n = (i, j, k, l, 1);
// every ray stays exactly where LFToolbox puts it. EstCamDistortionV is [k1 k2 k3 b1 b2], our order. The decoded
// geometry is LFToolbox's (CalOptions.LFSize = [views down, views across, pixel rows, pixel columns, channels]): the
// calibration holds only for light fields LFToolbox decoded with that camera's grid, and rectify checks the size.
// Poses and the board are not imported (LFToolbox's board may have unequal square sides), and a warning says so.

#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/calibrate/calibration.h"

namespace lfsp::calibrate {

// Whether a JSON document is an LFToolbox calibration (it holds EstCamIntrinsicsH).
bool IsLfToolboxCalibration(const nlohmann::json& json);

// lfsp::Error naming `source` and the field for a missing or malformed EstCamIntrinsicsH, EstCamDistortionV or
// CalOptions.LFSize, or a singular matrix.
Calibration CalibrationFromLfToolbox(const nlohmann::json& calinfo, const std::string& source);

}  // namespace lfsp::calibrate
