#include "json_text.h"

#include "lfsp/core/error.h"

namespace lfsp::decode {

nlohmann::json ParseLytroJson(std::string_view text, const std::string& source) {
  const std::size_t last_brace = text.rfind('}');
  if (last_brace == std::string_view::npos) {
    throw Error(source + ": no JSON object in the metadata text (no closing '}')");
  }
  const std::string_view object = text.substr(0, last_brace + 1);
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(object.begin(), object.end());
  } catch (const nlohmann::json::exception& e) {
    throw Error(source + ": invalid JSON metadata: " + e.what());
  }
  if (!value.is_object()) throw Error(source + ": JSON metadata is not an object");
  return value;
}

}  // namespace lfsp::decode
