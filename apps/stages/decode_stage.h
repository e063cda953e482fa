#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/decode/capture_decoder.h"

namespace lfsp::stages {

struct DecodeStageResult {
  Bundle bundle;           // the decoded light field
  nlohmann::json summary;  // the decoder's summary (capture, white image and why, grid, report, timings)
};

// Decodes a raw capture into a light field whose samples are rounded to the precision a bundle stores them with
// (RoundToStoredPrecision): what later stages compute on it in memory is what they compute on the written file.
// With `out`, also writes it (any light-field format; `bit_depth` for PNG views and ESLF) and OUT.summary.json
// (the decoder's summary with `extra` merged in, e.g. the parameters as the user gave them).
DecodeStageResult RunDecodeStage(const std::filesystem::path& capture, const decode::CaptureDecodeOptions& options,
                                 const std::filesystem::path& out = {}, int bit_depth = 16,
                                 const nlohmann::json& extra = {});

}  // namespace lfsp::stages
