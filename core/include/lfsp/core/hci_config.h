#pragma once

#include <filesystem>
#include <string>

#include "lfsp/core/metadata.h"

namespace lfsp {

// The HCI benchmark's parameters.cfg: INI sections of `key = value`. Numbers become JSON numbers, the rest strings.
Metadata ParseHciConfig(const std::string& text, const std::string& source_name);
Metadata ReadHciConfig(const std::filesystem::path& path);

// Writes every object-valued section of `metadata` whose values are scalars, in the same INI shape.
std::string FormatHciConfig(const Metadata& metadata);

}  // namespace lfsp
