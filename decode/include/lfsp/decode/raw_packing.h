#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lfsp::decode {

// How raw sensor pixels are packed into bytes in Lytro files (see
// shared/reference/lytro-format.md §1.3).
//
// The pixel stream is row-major and continuous: Lytro rows are NOT padded to a
// byte or group boundary, so the image width does not matter to the packing,
// only the total pixel count does.
//
// * kBits12BigEndian (F01, "12-bit big-endian"): 3 bytes hold 2 pixels,
//     p0 = b0 << 4 | b1 >> 4,   p1 = (b1 & 0x0F) << 8 | b2.
// * kBits10Illum (Illum, "10-bit little-endian"): 5 bytes hold 4 pixels: first
// the four most significant bytes,
//   then one byte with the four 2-bit remainders, pixel i in bits 2i..2i+1:
//     p_i = b_i << 2 | (b4 >> 2i) & 3.
// * kBits16LittleEndian (written by some third-party extractors): 2 bytes per
// pixel, little-endian, any value.
//
// Trailing partial group: when the pixel count is not a multiple of the group
// (2 pixels for 12-bit, 4 for 10-bit), the stream still ends with a whole
// group; the missing pixels are packed as 0 and ignored on unpacking. So the
// packed size is ceil(pixels / group) * group_bytes (PackedByteCount), never a
// fraction.
enum class RawPacking { kBits12BigEndian, kBits10Illum, kBits16LittleEndian };

// "12-bit big-endian" / "10-bit Illum" / "16-bit little-endian", for messages
// and `lfsp info`.
std::string_view ToString(RawPacking packing);

int BitsPerPixel(RawPacking packing);             // 12, 10, 16
std::uint16_t MaxPixelValue(RawPacking packing);  // 4095, 1023, 65535

// Exact byte count of `pixel_count` packed pixels, including the padded
// trailing group.
std::size_t PackedByteCount(RawPacking packing, std::size_t pixel_count);

// Unpacks `packed` into `pixels` (pixels.size() pixels). Throws lfsp::Error
// naming `source` and the expected and actual byte counts unless packed.size()
// == PackedByteCount(packing, pixels.size()). Parallel (OpenMP).
void UnpackRaw(RawPacking packing, std::span<const std::uint8_t> packed, std::span<std::uint16_t> pixels,
               const std::string& source);
std::vector<std::uint16_t> UnpackRaw(RawPacking packing, std::span<const std::uint8_t> packed, std::size_t pixel_count,
                                     const std::string& source);

// The sum of the levels of `pixel_count` pixels packed as `packing`, read from `in` and unpacked a block of 64 Ki
// pixels at a time: a white image's mean level without its unpacked copy (the white-image database measured six
// full-size Illum whites on every decode by unpacking each whole). Exact: the same sum as over UnpackRaw's pixels.
// Throws lfsp::Error naming `source` when `in` ends before PackedByteCount(packing, pixel_count) bytes.
std::uint64_t SumPackedLevels(RawPacking packing, std::istream& in, std::size_t pixel_count, const std::string& source);

// Packs `pixels` (values must fit in BitsPerPixel bits, otherwise lfsp::Error
// naming `source` and the first offending pixel index) into exactly
// PackedByteCount(packing, pixels.size()) bytes.
std::vector<std::uint8_t> PackRaw(RawPacking packing, std::span<const std::uint16_t> pixels, const std::string& source);

// A raw sensor image: width x height pixels, row-major from the top-left,
// values as stored (not normalised).
struct RawImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint16_t> pixels;

  std::size_t PixelCount() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::uint16_t at(int y, int x) const {
    return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
  }
};

// Unpacks a width x height image; throws lfsp::Error (naming `source`) on
// non-positive sizes or a buffer whose size is not PackedByteCount(packing,
// width * height).
RawImage UnpackRawImage(RawPacking packing, std::span<const std::uint8_t> packed, int width, int height,
                        const std::string& source);

}  // namespace lfsp::decode
