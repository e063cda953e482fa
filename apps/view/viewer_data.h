#pragma once

// What `lfsp view` loads once and serves: the light field (with labels, disparity and confidence when there are
// any) resolved from one input, and the same data as compact binary arrays the page reads in one request each.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "recolor_request.h"

namespace lfsp::view {

// The files the viewer reads. A pipeline output folder (it holds segmentation.h5) gives its segmentation.h5 (light
// field, labels, disparity) and disparity_confidence.pfm; any other path is a light field.
struct ViewerSources {
  std::filesystem::path light_field;
  std::filesystem::path labels;      // "" = the light field's own, if any
  std::filesystem::path disparity;   // "" = the light field's own, if any
  std::filesystem::path confidence;  // "" = none
};

// Resolves the command's arguments; throws lfsp::Error naming a path that does not exist.
ViewerSources ResolveSources(const std::filesystem::path& input, const std::filesystem::path& labels,
                             const std::filesystem::path& disparity);

struct ViewerData {
  ViewerSources sources;
  cli::RecolorRequest recolor_base;  // input and labels as `lfsp recolor` must be given them to edit this data
  Bundle bundle;                     // the views shown (and edited on export), with labels when there are any
  std::optional<DisparityMap> confidence;

  // The page's arrays, little-endian, row-major as the light field ([v][u][y][x]).
  std::vector<std::uint8_t> views_rgb8;     // display-encoded sRGB, 3 bytes per pixel
  std::vector<std::uint8_t> labels_packed;  // uint16 when every label fits below 65535, else int32; -1 -> max
  int label_bytes = 0;                      // 2 or 4; 0 = no labels
  nlohmann::json meta;                      // shapes, types and names, for /api/meta
};

// Loads everything the page shows, once. Labels go through the loader `lfsp recolor` uses, so the views kept are
// the ones the exported command line edits.
ViewerData LoadViewerData(const ViewerSources& sources);

// The disparity or confidence map as float32 bytes, empty without one.
std::string FloatBytes(const std::optional<DisparityMap>& map);

}  // namespace lfsp::view
