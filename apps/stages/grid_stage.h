#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/raw_input.h"

namespace lfsp::stages {

struct GridStageResult {
  decode::LensletGrid grid;
  nlohmann::json document;  // what `lfsp grid --out` writes: input, format, metadata schema, kind, grid, seconds
};

// The lenslet lattice of a white image or an ordinary capture. `kind` is auto | white | capture (see `lfsp grid`);
// `plain` says how to read a plain raw image. lfsp::Error naming the input when no lattice is found.
GridStageResult RunGridStage(const std::filesystem::path& input, const std::string& kind,
                             const decode::PlainRawOptions& plain);

}  // namespace lfsp::stages
