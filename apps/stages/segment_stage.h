#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/lfsp.h"

namespace lfsp::stages {

struct SegmentStageOptions {
  segment::LfspParams params;
  int epi_row = -1;                  // image row of the horizontal EPI picture; -1 = the middle
  int epi_column = -1;               // image column of the vertical EPI picture; -1 = the middle
  std::filesystem::path labels_png;  // also one 16-bit label PNG per view into this folder; empty = none
};

struct SegmentStageResult {
  segment::LfspResult lfsp;
  nlohmann::ordered_json summary;  // what OUT.summary.json holds
};

// Light-field superpixels of `light_field` given its centre-view `disparity` (recorded as `disparity_source`).
// Writes OUT.h5 (the light field, the disparity, the labels and, in the metadata, the parameters: self-contained for
// `lfsp evaluate segmentation`), OUT.planes.json, the boundary pictures OUT.overlay_centre.png, OUT.overlay_epi_h.png
// and OUT.overlay_epi_v.png, optional label PNGs, and OUT.summary.json (`summary` first). The light field is moved
// into the written bundle and back, never copied; on return its metadata holds the segmentation record, as the
// bundle's does (metadata["lfsp_segment"]: parameters and disparity source).
SegmentStageResult RunSegmentStage(LightField& light_field, const DisparityMap& disparity,
                                   const std::string& disparity_source, const SegmentStageOptions& options,
                                   const std::filesystem::path& out, nlohmann::ordered_json summary = {});

}  // namespace lfsp::stages
