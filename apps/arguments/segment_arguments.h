#pragma once

#include <CLI/CLI.hpp>

#include "lfsp/segment/params.h"

namespace lfsp::cli {

// Every LFSP parameter (paper Table II and the solver's), as `lfsp segment` and the Python module spell them:
// --size, --lambda-p, ... with their defaults.
void AddLfspParameters(CLI::App* command, segment::LfspParams& params);

}  // namespace lfsp::cli
