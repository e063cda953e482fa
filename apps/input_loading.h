#pragma once

#include <filesystem>

#include "lfsp/core/load.h"

namespace lfsp::cli {

// What every command's light-field input is read with: the global `--views-pattern` (set by lfsp_main before the
// command runs). Commands load through LoadInput so that the option reaches every one of them.
LoadOptions& GlobalLoadOptions();

Bundle LoadInput(const std::filesystem::path& path);

}  // namespace lfsp::cli
