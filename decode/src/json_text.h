#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace lfsp::decode {

// Parses JSON metadata text as Lytro writes it. White-image .TXT files may
// carry trailing bytes after the final
// '}' (NULs, a checksum): everything after the last '}' is ignored. Throws
// lfsp::Error naming `source` (and the parser's byte position) if the text is
// not one JSON object.
nlohmann::json ParseLytroJson(std::string_view text, const std::string& source);

}  // namespace lfsp::decode
