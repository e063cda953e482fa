#pragma once

// The page's export: the edited light field written by `lfsp recolor`'s own stage, the selection as a label list
// and a centre-view mask, and the command line that writes the same light field.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "view/viewer_data.h"

namespace lfsp::view {

// `edit` is the page's request: {"label_ids": [...], "hue", "saturation", "value", "space", "feather"}. Writes into
// `folder` recolored.h5 (+ previews and summary, as `lfsp recolor` does), selection.json and selection_mask.png.
// Returns {"command": one shell line, "arguments": [...after lfsp], "files": [...]}. Throws lfsp::Error on a bad
// request (unknown label, bad number).
nlohmann::json ExportEdit(const ViewerData& data, const nlohmann::json& edit, const std::filesystem::path& folder);

}  // namespace lfsp::view
