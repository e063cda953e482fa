#pragma once

#include <cstddef>
#include <string>

namespace lfsp {

// The offset of the first byte of `text` that does not belong to valid UTF-8 (RFC 3629, as PrintableText reads it),
// or std::string::npos. Text read from a file into metadata must be UTF-8: nlohmann::json cannot write anything else
// (its dump throws a type_error).
std::size_t FirstNonUtf8Byte(const std::string& text);

}  // namespace lfsp
