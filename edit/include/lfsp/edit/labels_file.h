#pragma once

#include <filesystem>

#include "lfsp/core/light_field.h"

namespace lfsp::edit {

// Reads only the per-ray labels of an HDF5 file, without loading its light field: dataset `labels` (an lfsp bundle,
// as `lfsp segment` writes it) or `GT_LABELS` (the old HCI layout), nv x nu x H x W of any integer type.
// Throws lfsp::Error naming the file if it is missing, not HDF5, has neither dataset or the wrong rank.
Labels ReadLabelsFile(const std::filesystem::path& path);

// Throws lfsp::Error naming `what` unless `labels` has the light field's views and view size.
void CheckLabelsMatch(const Labels& labels, const LightFieldShape& shape, const std::string& what);

}  // namespace lfsp::edit
