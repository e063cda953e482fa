#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/view_crop.h"

namespace lfsp::cli {

// `--views N` (central N x N; 0 = chosen from the weights) on every command that takes a light field.
void AddViewsOption(CLI::App* command, int& views);

// Keeps the views a stage should process (ChooseViews) of the bundle's light field and labels, in place, logs the
// choice naming `source`, and returns it for the summary.
nlohmann::json SelectViews(Bundle& bundle, int requested, const std::string& source);

// Logs a choice of views naming `source`, and returns it for the summary (what SelectViews returns).
nlohmann::json ViewChoiceSummary(const ViewChoice& choice, const std::string& source);

}  // namespace lfsp::cli
