#pragma once

#include <filesystem>

#include "lfsp/core/views_folder.h"

namespace lfsp::internal {

// Writes the views (and weights, parameters.cfg) into an existing folder, with no atomic rename: the caller owns
// the temporary folder (WriteViewsFolder, SaveLightField).
void WriteViewsInto(const LightField& light_field, const std::filesystem::path& folder,
                    const ViewsFolderOptions& options);

// Refuses to replace an existing path that is not a views folder (nor empty): we never clobber a user's folder.
void CheckReplaceableOutputFolder(const std::filesystem::path& folder);

}  // namespace lfsp::internal
