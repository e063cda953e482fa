#pragma once

#include <filesystem>

#include "lfsp/core/light_field.h"

namespace lfsp {

// PFM disparity maps as the HCI benchmark writes them: "Pf" (one channel), width height, a negative scale for
// little-endian, then float rows from the bottom row of the image to the top. Big-endian files (positive scale)
// are read too. A three-channel "PF" file is rejected for disparity.
DisparityMap ReadPfm(const std::filesystem::path& path);
void WritePfm(const DisparityMap& disparity, const std::filesystem::path& path);

// A disparity map as a 16-bit grey PNG for tools that do not read PFM: 0 = no disparity (NaN), 1..65535 spread
// linearly over the map's finite range, which the PNG's text chunks give: lfsp:disparity_min, lfsp:disparity_max
// (px per view step) and lfsp:encoding (the formula d = min + (value - 1) / 65534 * (max - min)). Rows top first.
void WriteDisparityPng16(const DisparityMap& disparity, const std::filesystem::path& path);

}  // namespace lfsp
