#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/depth/depth_estimator.h"

namespace lfsp::cli {

// The options of `lfsp depth` that choose the method, as the command line (and the Python module, which parses its
// keywords through the same options) spells them.
struct DepthArguments {
  std::optional<float> dmin;
  std::optional<float> dmax;
  bool no_occlusion = false;
  bool winner_take_all = false;
  std::vector<float> channel_weights;  // empty: automatic
  std::string sampler = "automatic";
  depth::DepthOptions method;
};

void AddDepthArguments(CLI::App* command, DepthArguments& arguments);

// The method options the arguments ask for; lfsp::Error when only one of --dmin and --dmax is given.
depth::DepthOptions ToDepthOptions(const DepthArguments& arguments);

}  // namespace lfsp::cli
