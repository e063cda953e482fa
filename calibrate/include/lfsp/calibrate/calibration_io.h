#pragma once

// The calibration file (JSON): the intrinsic matrix H (5x5, rows), the distortion, the decoded geometry it belongs
// to, the board, the camera setting, one pose per capture with its RMS ray reprojection error and the views used,
// the stages' errors and any warnings. Format tag "lfsp-calibration", version 1.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/calibrate/calibration.h"

namespace lfsp::calibrate {

nlohmann::json CalibrationToJson(const Calibration& calibration);

// Throws lfsp::Error naming `source` and the field when the JSON is not a valid calibration. LFToolbox's CalInfo.json
// is accepted too (lftoolbox_calibration.h).
Calibration CalibrationFromJson(const nlohmann::json& json, const std::string& source);

// Written through a temporary file renamed when complete.
void WriteCalibration(const Calibration& calibration, const std::filesystem::path& path);
Calibration ReadCalibration(const std::filesystem::path& path);

nlohmann::json MatrixToJson(const Matrix5d& H);
// 5 rows of 5 finite numbers forming an invertible matrix, else lfsp::Error naming `source` and `field`.
Matrix5d MatrixFromJson(const nlohmann::json& rows, const std::string& field, const std::string& source);

}  // namespace lfsp::calibrate
