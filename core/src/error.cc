#include "lfsp/core/error.h"

#include "lfsp/core/utf8.h"

namespace lfsp {
namespace {

// Length of the valid UTF-8 sequence that starts at text[i], or 0 (RFC 3629: no overlong forms, no surrogates, at
// most U+10FFFF).
std::size_t Utf8SequenceAt(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // range of the first continuation byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

std::string PrintableText(const std::string& text) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7F) {
      out += text[i++];
      continue;
    }
    const std::size_t length = byte >= 0x80 ? Utf8SequenceAt(text, i) : 0;
    if (length > 0) {
      out.append(text, i, length);
      i += length;
      continue;
    }
    out += "\\x";
    out += kHex[byte >> 4];
    out += kHex[byte & 0xF];
    ++i;
  }
  return out;
}

std::size_t FirstNonUtf8Byte(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    if (static_cast<unsigned char>(text[i]) < 0x80) {
      ++i;
      continue;
    }
    const std::size_t length = Utf8SequenceAt(text, i);
    if (length == 0) return i;
    i += length;
  }
  return std::string::npos;
}

std::string FileMessage(const std::string& path, const std::string& problem) { return path + ": " + problem; }

void ThrowFileError(const std::string& path, const std::string& problem) { throw Error(FileMessage(path, problem)); }

namespace {
std::string KeepApiName(const std::string& api_name) { return api_name; }
OptionNamer g_option_namer = KeepApiName;
}  // namespace

std::string OptionName(const std::string& api_name) { return g_option_namer(api_name); }

void SetOptionNamer(OptionNamer namer) { g_option_namer = namer != nullptr ? namer : KeepApiName; }

}  // namespace lfsp
