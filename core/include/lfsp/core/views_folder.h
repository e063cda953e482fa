#pragma once

#include <filesystem>
#include <string>

#include "lfsp/core/light_field.h"

namespace lfsp {

// A light field as a folder of views: HCI style (input_Cam%03d.png numbered row-major, parameters.cfg with the
// angular size num_cams_x / num_cams_y, else a square), or any naming views_naming.h detects, or `views_pattern`
// (--views-pattern). The detected naming is logged; parameters.cfg, when present, becomes the metadata. Every header is
// checked before anything is allocated; views are decoded in parallel. Any image format OpenImageIO reads works as a
// view.
LightField ReadViewsFolder(const std::filesystem::path& folder, const std::string& views_pattern = "");

struct ViewsFolderOptions {
  int bit_depth = 8;               // 8 or 16 bits per sample
  std::string extension = ".png";  // ".png" or ".tif" (16-bit TIFF views for tools that want them)
};

// Writes input_Cam%03d.png (and parameters.cfg from the metadata) into `folder`, through a temporary folder renamed
// when complete. An existing folder is replaced only if it looks like a views folder (or is empty).
void WriteViewsFolder(const LightField& light_field, const std::filesystem::path& folder,
                      const ViewsFolderOptions& options = {});

bool LooksLikeViewsFolder(const std::filesystem::path& folder);

}  // namespace lfsp
