#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/depth/depth_estimator.h"

namespace lfsp::depth {

// Where `lfsp depth --out DISP.pfm` puts its results: the disparity itself, a TURBO colour-mapped preview over the
// disparity range (DISP.png), the confidence map (DISP_confidence.pfm) and the JSON summary (DISP.summary.json).
struct DepthOutputPaths {
  std::filesystem::path disparity;
  std::filesystem::path preview;
  std::filesystem::path confidence;
};

DepthOutputPaths OutputPathsFor(const std::filesystem::path& disparity_pfm);

// Writes disparity, preview and confidence, each through a temporary file renamed when complete.
void WriteDepthOutputs(const DepthResult& result, const DepthOutputPaths& paths);

// The options as JSON, for summaries (every parameter, so a run can be repeated).
nlohmann::json ToJson(const DepthOptions& options);

// What the estimate chose automatically, as JSON for summaries (in this order): the noise estimates and the choices
// that follow them (presmoothing, sampler, excluded ring, detail and channel weights), the occlusion radius and the
// semi-global penalties.
nlohmann::ordered_json AutomaticChoicesToJson(const DepthResult& result);

}  // namespace lfsp::depth
