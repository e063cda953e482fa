// Fuzz target: grid files given to `lfsp decode --grid` (ReadGivenGrid: lfsp's grid.json or LFToolbox's
// LensletGridModel), read for a small sensor so that a plausible grid is also sliced into lens ranges.

#include "../../core/fuzz/fuzz_file.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/given_grid.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::decode::ReadGivenGrid(FuzzInputFile(data, size, ".json"), 1024, 1024, 511.5, 511.5);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
