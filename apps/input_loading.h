#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/core/load.h"

namespace lfsp::cli {

// What every command's light-field input is read with: the global `--views-pattern` (set by lfsp_main before the
// command runs). Commands load through LoadInput so that the option reaches every one of them.
LoadOptions& GlobalLoadOptions();

Bundle LoadInput(const std::filesystem::path& path);

// LoadInput keeping only the views a stage should process (LoadCentralViews: an .h5 bundle is read only for them),
// as SelectViews would keep them; logs the choice and puts it in `views_summary`, as SelectViews returns it.
Bundle LoadSelectedViews(const std::filesystem::path& path, int requested, nlohmann::json& views_summary);

}  // namespace lfsp::cli
