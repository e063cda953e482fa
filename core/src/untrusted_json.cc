#include "lfsp/core/untrusted_json.h"

#include "lfsp/core/error.h"

namespace lfsp {
namespace {

// Throws if the brackets of `text` nest deeper than kMaxJsonNesting. Brackets inside strings do not count; text that
// is not JSON at all is left for the parser to refuse.
void RequireShallowNesting(std::string_view text, const std::string& source) {
  int depth = 0;
  bool in_string = false;
  bool escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        ThrowFileError(source, "JSON nested more than " + std::to_string(kMaxJsonNesting) + " levels deep (at byte " +
                                   std::to_string(i) + ")");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

}  // namespace

nlohmann::json ParseUntrustedJson(std::string_view text, const std::string& source) {
  RequireShallowNesting(text, source);
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& e) {
    ThrowFileError(source, std::string("not valid JSON: ") + e.what());
  }
}

nlohmann::json ParseUntrustedJsonObject(std::string_view text, const std::string& source) {
  nlohmann::json document = ParseUntrustedJson(text, source);
  if (!document.is_object()) ThrowFileError(source, "not a JSON object");
  return document;
}

}  // namespace lfsp
