// Fuzz target: HCI parameters.cfg text (ParseHciConfig).

#include <string>

#include "../../decode/fuzz/fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hci_config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)lfsp::ParseHciConfig(std::string(reinterpret_cast<const char*>(data), size), "fuzz.cfg");
  } catch (const lfsp::Error&) {
  }
  return 0;
}
