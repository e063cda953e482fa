#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/edit/recolor.h"

namespace lfsp::stages {

struct RecolorStageOptions {
  std::vector<std::int32_t> selection;  // the labels to recolour
  nlohmann::ordered_json how;           // how they were chosen, for the summary
  edit::RecolorOptions recolor;
  int bit_depth = 8;  // of a views folder or ESLF output
};

struct RecolorStageResult {
  edit::RecolorStats stats;
  cv::Mat before;  // centre view before and after, display-encoded float RGB
  cv::Mat after;
  nlohmann::ordered_json summary;  // what OUT.summary.json holds
};

// Recolours the selected superpixels of `bundle` (which holds the labels) in every view, in place, and writes the
// bundle to OUT (any light-field format), the centre view before and after as OUT.before.png and OUT.after.png,
// and OUT.summary.json (`summary` first).
RecolorStageResult RunRecolorStage(Bundle& bundle, const RecolorStageOptions& options, const std::filesystem::path& out,
                                   nlohmann::ordered_json summary = {});

}  // namespace lfsp::stages
