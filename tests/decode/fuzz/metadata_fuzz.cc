// Fuzz target: Lytro metadata documents (white-image TXT, frame JSON, tables of contents with inline metadata).

#include <string_view>

#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lytro_metadata.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const lfsp::decode::LytroMetadata md =
        lfsp::decode::ParseMetadataDocument(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.TXT");
    if (md.raw_format) (void)md.RequireRawFormat();
    if (md.mla) (void)md.RequireMla().ApproxSpacingPixels();
  } catch (const lfsp::Error&) {
  }
  return 0;
}
