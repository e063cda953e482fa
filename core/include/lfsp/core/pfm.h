#pragma once

#include <filesystem>

#include "lfsp/core/light_field.h"

namespace lfsp {

// PFM disparity maps as the HCI benchmark writes them: "Pf" (one channel), width height, a negative scale for
// little-endian, then float rows from the bottom row of the image to the top. Big-endian files (positive scale)
// are read too. A three-channel "PF" file is rejected for disparity.
DisparityMap ReadPfm(const std::filesystem::path& path);
void WritePfm(const DisparityMap& disparity, const std::filesystem::path& path);

}  // namespace lfsp
