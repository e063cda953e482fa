#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "lfsp/simulate/simulate.h"

namespace lfsp::cli {

// The options of `lfsp simulate` that say what to render (not where), as the command line and the Python module
// spell them.
struct SimulateArguments {
  simulate::SimulateOptions library;
  std::string size = "256x256";
  std::string storage = "float32";
};

void AddSimulateArguments(CLI::App* command, SimulateArguments& arguments);

// The library's options; lfsp::Error for a size that is not WxH.
simulate::SimulateOptions ToSimulateOptions(const SimulateArguments& arguments);

}  // namespace lfsp::cli
