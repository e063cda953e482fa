#include "png_bytes.h"

#include <zlib.h>

namespace lfsp::testing {
namespace {

std::string BigEndian32(std::uint32_t v) {
  return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                     static_cast<char>(v)};
}

// One chunk: length, type, data and the CRC of type and data.
std::string PngChunk(const std::string& type, const std::string& data) {
  const std::string body = type + data;
  const auto crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size())));
  return BigEndian32(static_cast<std::uint32_t>(data.size())) + body + BigEndian32(crc);
}

}  // namespace

std::string PngDeclaring(std::uint32_t width, std::uint32_t height) {
  return "\x89PNG\r\n\x1a\n" +
         PngChunk("IHDR", BigEndian32(width) + BigEndian32(height) + std::string("\x08\x02\x00\x00\x00", 5)) +
         PngChunk("IDAT", "") + PngChunk("IEND", "");
}

}  // namespace lfsp::testing
