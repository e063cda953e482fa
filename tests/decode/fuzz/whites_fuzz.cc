// Fuzz target: white-image database files (whites.json, ReadWhiteImageDatabase).

#include "../../core/fuzz/fuzz_file.h"
#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/white_database.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::decode::ReadWhiteImageDatabase(FuzzInputFile(data, size, ".json"));
  } catch (const lfsp::Error&) {
  }
  return 0;
}
