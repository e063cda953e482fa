#pragma once

// The calibration file (JSON): the intrinsic matrix H (5x5, rows), the distortion, the decoded geometry it belongs
// to, the board, the camera setting, one pose per capture with its RMS ray reprojection error and the views used,
// the stages' errors and any warnings. Format tag "lfsp-calibration", version 1.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/calibrate/calibration.h"

namespace lfsp::calibrate {

nlohmann::json CalibrationToJson(const Calibration& calibration);

// Throws lfsp::Error naming `source` and the field when the JSON is not a valid calibration.
Calibration CalibrationFromJson(const nlohmann::json& json, const std::string& source);

// Written through a temporary file renamed when complete.
void WriteCalibration(const Calibration& calibration, const std::filesystem::path& path);
Calibration ReadCalibration(const std::filesystem::path& path);

nlohmann::json MatrixToJson(const Matrix5d& H);

}  // namespace lfsp::calibrate
