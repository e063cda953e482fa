#pragma once

#include <filesystem>

#include "lfsp/core/light_field.h"

namespace lfsp {

// A light field as a folder of views, HCI style: input_Cam%03d.png numbered row-major plus parameters.cfg.
// The angular size is read from parameters.cfg (num_cams_x / num_cams_y); without it the views must form a square.
// Views are decoded in parallel. Any image format OpenImageIO reads works as a view if named input_CamNNN.<ext>.
LightField ReadViewsFolder(const std::filesystem::path& folder);

struct ViewsFolderOptions {
  int bit_depth = 8;  // 8 or 16 bits per sample in the PNG files
};

// Writes input_Cam%03d.png (and parameters.cfg from the metadata) into `folder`, through a temporary folder renamed
// when complete. An existing folder is replaced only if it looks like a views folder (or is empty).
void WriteViewsFolder(const LightField& light_field, const std::filesystem::path& folder,
                      const ViewsFolderOptions& options = {});

bool LooksLikeViewsFolder(const std::filesystem::path& folder);

}  // namespace lfsp
