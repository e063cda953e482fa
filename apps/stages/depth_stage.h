#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/depth/depth_estimator.h"

namespace lfsp::stages {

struct DepthStageResult {
  depth::DepthResult estimate;
  nlohmann::ordered_json summary;  // what DISP.summary.json holds
};

// Estimates the centre-view disparity of the bundle's light field and writes DISP.pfm, its colour-mapped preview
// DISP.png, DISP_confidence.pfm and DISP.summary.json (`summary` first: the caller's fields, e.g. the input). When
// the bundle carries a ground-truth disparity of the view size, the summary scores the estimate against it.
DepthStageResult RunDepthStage(const Bundle& bundle, const depth::DepthOptions& options,
                               const std::filesystem::path& disparity_pfm, nlohmann::ordered_json summary = {});

}  // namespace lfsp::stages
