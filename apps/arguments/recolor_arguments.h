#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "lfsp/edit/recolor.h"

namespace lfsp::cli {

// How `lfsp recolor` changes the selected superpixels (not which ones, nor where it writes), as the command line and
// the Python module spell it.
struct RecolorArguments {
  float hue = 0.0f;
  float saturation = 1.0f;
  float value = 1.0f;
  std::string space = "lch";
  float feather = 0.0f;
  bool no_weights = false;
};

void AddRecolorArguments(CLI::App* command, RecolorArguments& arguments);

// The recolour options; lfsp::Error for an unknown colour space, a negative factor or feather width.
edit::RecolorOptions ToRecolorOptions(const RecolorArguments& arguments);

}  // namespace lfsp::cli
