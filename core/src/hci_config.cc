#include "lfsp/core/hci_config.h"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/utf8.h"

namespace lfsp {
namespace {

std::string Trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

// "7.0" -> 7.0, "9" -> 9, anything else stays text.
Metadata ParseValue(const std::string& text) {
  if (text.empty()) return text;
  long long integer = 0;
  auto [int_end, int_error] = std::from_chars(text.data(), text.data() + text.size(), integer);
  if (int_error == std::errc() && int_end == text.data() + text.size()) return integer;
  double real = 0.0;
  auto [real_end, real_error] = std::from_chars(text.data(), text.data() + text.size(), real);
  if (real_error == std::errc() && real_end == text.data() + text.size()) return real;
  return text;
}

}  // namespace

Metadata ParseHciConfig(const std::string& text, const std::string& source_name) {
  Metadata result = Metadata::object();
  std::istringstream lines(text);
  std::string line;
  std::string section = "general";
  int line_number = 0;
  while (std::getline(lines, line)) {
    ++line_number;
    // Its sections, keys and values become metadata, which must be UTF-8 to be written anywhere (a Latin-1 "ü" in
    // authors = ... made info, convert and the angular size's own message end as internal failures).
    if (const std::size_t bad = FirstNonUtf8Byte(line); bad != std::string::npos) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(line[bad]));
      ThrowFileError(source_name, "line " + std::to_string(line_number) + " is not UTF-8 text (byte " + byte +
                                      " at column " + std::to_string(bad + 1) + "); save the file as UTF-8");
    }
    const std::string trimmed = Trim(line);
    if (trimmed.empty() || trimmed[0] == '#' || trimmed[0] == ';') continue;
    if (trimmed.front() == '[') {
      if (trimmed.back() != ']' || trimmed.size() < 3)
        ThrowFileError(source_name, "line " + std::to_string(line_number) + ": malformed section header");
      section = Trim(trimmed.substr(1, trimmed.size() - 2));
      result[section] = Metadata::object();
      continue;
    }
    const auto equals = trimmed.find('=');
    if (equals == std::string::npos)
      ThrowFileError(source_name, "line " + std::to_string(line_number) + ": expected 'key = value'");
    result[section][Trim(trimmed.substr(0, equals))] = ParseValue(Trim(trimmed.substr(equals + 1)));
  }
  return result;
}

Metadata ReadHciConfig(const std::filesystem::path& path) { return ParseHciConfig(ReadWholeFile(path), path.string()); }

std::string FormatHciConfig(const Metadata& metadata) {
  std::ostringstream out;
  if (!metadata.is_object()) return "";
  bool first = true;
  for (const auto& [section, values] : metadata.items()) {
    if (!values.is_object()) continue;
    if (!first) out << "\n";
    first = false;
    out << "[" << section << "]\n";
    for (const auto& [key, value] : values.items()) {
      if (value.is_string()) {
        out << key << " = " << value.get<std::string>() << "\n";
      } else if (value.is_number() || value.is_boolean()) {
        out << key << " = " << value.dump() << "\n";
      }
    }
  }
  return out.str();
}

}  // namespace lfsp
