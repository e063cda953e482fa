#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "lfsp/edit/refocus.h"

namespace lfsp::cli {

// How `lfsp refocus` resamples (--interpolation, --no-weights), as the command line and the Python module spell it.
struct RefocusArguments {
  std::string interpolation = "linear";
  bool no_weights = false;
};

void AddRefocusArguments(CLI::App* command, RefocusArguments& arguments);
edit::RefocusOptions ToRefocusOptions(const RefocusArguments& arguments);

// lfsp::Error naming `option` unless `disparity` is finite and within +-1000 px per view step: beyond that every ray
// leaves every view, so the value is a typo, not a request.
void RequireRefocusDisparity(float disparity, const std::string& option);

}  // namespace lfsp::cli
