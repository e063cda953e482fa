#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/edit/refocus.h"

namespace lfsp::stages {

struct RefocusStageOptions {
  std::vector<float> disparities;  // focal-stack slices, px per view step; empty = no focal stack
  // The all-in-focus image needs a disparity map (with where it came from, for the summary); null = none.
  const DisparityMap* all_in_focus_disparity = nullptr;
  std::string all_in_focus_source;
  bool occlusion_aware = true;
  std::optional<float> shear;         // also the light field sheared by this refocus level ...
  std::filesystem::path sheared_out;  // ... written here (any light-field format)
  edit::RefocusOptions refocus;       // interpolation, ray weights
  int bit_depth = 8;                  // of the PNGs
};

struct RefocusStageResult {
  std::vector<cv::Mat> slices;     // the focal stack (float, the light field's transfer), for reports
  nlohmann::ordered_json summary;  // what DIR/summary.json holds
};

// Shift-and-sum refocusing into the folder `out` (written whole or not at all): DIR/refocus_NN_dSHIFT.png per
// slice, DIR/all_in_focus.png, the sheared light field, and DIR/summary.json (`summary` first).
RefocusStageResult RunRefocusStage(const Bundle& bundle, const RefocusStageOptions& options,
                                   const std::filesystem::path& out, nlohmann::ordered_json summary = {});

// The file name of focal-stack slice `index`, focused at `disparity`: refocus_02_d+0.500.png.
std::string FocalStackSliceName(std::size_t index, float disparity);

// "linear" / "cubic" (the names of --interpolation).
ShearInterpolation InterpolationFromName(const std::string& name);
std::string InterpolationName(ShearInterpolation interpolation);

}  // namespace lfsp::stages
