#include "json_text.h"

#include "lfsp/core/error.h"
#include "lfsp/core/untrusted_json.h"

namespace lfsp::decode {

nlohmann::json ParseLytroJson(std::string_view text, const std::string& source) {
  const std::size_t last_brace = text.rfind('}');
  if (last_brace == std::string_view::npos) {
    throw Error(source + ": no JSON object in the metadata text (no closing '}')");
  }
  const std::string_view object = text.substr(0, last_brace + 1);
  return ParseUntrustedJsonObject(object, source);
}

}  // namespace lfsp::decode
