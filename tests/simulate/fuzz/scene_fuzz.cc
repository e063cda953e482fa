// Fuzz target: scene JSON (the simulator's only parser of user files). Parses, and when the scene is valid renders
// a tiny light field, so the tracer also meets extreme but accepted values. Only lfsp::Error may escape the parser.

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/untrusted_json.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    // Parsed as LoadScene parses a file: nesting depth checked before the document is built.
    const nlohmann::json json =
        lfsp::ParseUntrustedJson(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
    const lfsp::simulate::Scene scene = lfsp::simulate::SceneFromJson(json, ".", "fuzz.json");
    lfsp::simulate::RenderOptions options;
    options.nu = options.nv = 3;
    options.width = 9;
    options.height = 7;
    options.supersampling = 1;
    (void)lfsp::simulate::RenderLightField(scene, options);
  } catch (const lfsp::Error&) {
  }
  return 0;
}
