// Fuzz target: the LFP container parser and everything built on it (reference resolution, metadata model,
// description). Bad input must end in lfsp::Error; any other exception or a crash is a bug.

#include <span>

#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lytro_capture.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const lfsp::decode::LytroCapture capture =
        lfsp::decode::OpenLytroContainerBytes(std::span<const std::uint8_t>(data, size), "fuzz.lfp");
    (void)capture.HoldsSummary();
    (void)capture.UnreferencedSections();
    if (capture.HasRawImage()) (void)capture.ReadRawImage();
  } catch (const lfsp::Error&) {
    // expected for malformed input
  }
  return 0;
}
