#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace lfsp {

// The deepest nesting of arrays and objects accepted in JSON that lfsp did not write itself. Every real file nests
// under ten levels; nlohmann::json copies, compares and dumps a document recursively, so a file of 200,000 nested
// '[' overflowed the stack (a 1 MB bundle metadata attribute crashed `lfsp info`).
inline constexpr int kMaxJsonNesting = 100;

// Parses JSON read from a file, an attribute or a request: bundle metadata, Lytro metadata, whites.json, scene,
// calibration and grid files. Throws lfsp::Error "<source>: ..." if the text nests deeper than kMaxJsonNesting
// (checked on the bytes, before anything is built) or is not valid JSON.
nlohmann::json ParseUntrustedJson(std::string_view text, const std::string& source);

// The same, and the document must be a JSON object, as every format lfsp reads is (`[1,2]` as bundle metadata
// reached code that indexes it by key).
nlohmann::json ParseUntrustedJsonObject(std::string_view text, const std::string& source);

}  // namespace lfsp
