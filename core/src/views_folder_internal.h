#pragma once

#include <filesystem>
#include <string>

#include "lfsp/core/views_folder.h"

namespace lfsp::internal {

inline constexpr const char* kConfigName = "parameters.cfg";

// "input_Cam004.png": the HCI name of a camera's view (prefix "input") or ray weights (prefix "weight").
std::string HciViewFileName(const char* prefix, int camera, const std::string& extension);

// Writes the views (and weights, parameters.cfg) into an existing folder, with no atomic rename: the caller owns
// the temporary folder (WriteViewsFolder, SaveLightField).
void WriteViewsInto(const LightField& light_field, const std::filesystem::path& folder,
                    const ViewsFolderOptions& options);

// Refuses to replace an existing path that is not a views folder (nor empty): we never clobber a user's folder.
void CheckReplaceableOutputFolder(const std::filesystem::path& folder);

}  // namespace lfsp::internal
