#include "lfsp/decode/raw_packing.h"

#include <algorithm>
#include <cstddef>
#include <string>

#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

struct Group {
  std::size_t pixels;
  std::size_t bytes;
};

Group GroupOf(RawPacking packing) {
  switch (packing) {
    case RawPacking::kBits12BigEndian:
      return {2, 3};
    case RawPacking::kBits10Illum:
      return {4, 5};
    case RawPacking::kBits16LittleEndian:
      return {1, 2};
  }
  throw Error("unknown raw packing");
}

// Signed loop counters for OpenMP; buffers never exceed 2^62 bytes.
using Index = std::ptrdiff_t;

// Below this many groups a parallel region costs more than it saves (small tiles, white images in tests, fuzzing).
constexpr Index kParallelGroups = 1 << 16;

// One group of packed bytes -> group.pixels pixels. `out` always has room for
// the whole group.
inline void UnpackGroup12(const std::uint8_t* b, std::uint16_t* out) {
  out[0] = static_cast<std::uint16_t>((b[0] << 4) | (b[1] >> 4));
  out[1] = static_cast<std::uint16_t>(((b[1] & 0x0F) << 8) | b[2]);
}

inline void UnpackGroup10(const std::uint8_t* b, std::uint16_t* out) {
  const unsigned low = b[4];
  for (int i = 0; i < 4; ++i) {
    out[i] = static_cast<std::uint16_t>((b[i] << 2) | ((low >> (2 * i)) & 3u));
  }
}

inline void UnpackGroup16(const std::uint8_t* b, std::uint16_t* out) {
  out[0] = static_cast<std::uint16_t>(b[0] | (b[1] << 8));
}

inline void PackGroup12(const std::uint16_t* p, std::uint8_t* b) {
  b[0] = static_cast<std::uint8_t>(p[0] >> 4);
  b[1] = static_cast<std::uint8_t>(((p[0] & 0x0F) << 4) | (p[1] >> 8));
  b[2] = static_cast<std::uint8_t>(p[1] & 0xFF);
}

inline void PackGroup10(const std::uint16_t* p, std::uint8_t* b) {
  unsigned low = 0;
  for (int i = 0; i < 4; ++i) {
    b[i] = static_cast<std::uint8_t>(p[i] >> 2);
    low |= (p[i] & 3u) << (2 * i);
  }
  b[4] = static_cast<std::uint8_t>(low);
}

inline void PackGroup16(const std::uint16_t* p, std::uint8_t* b) {
  b[0] = static_cast<std::uint8_t>(p[0] & 0xFF);
  b[1] = static_cast<std::uint8_t>(p[0] >> 8);
}

using UnpackFn = void (*)(const std::uint8_t*, std::uint16_t*);
using PackFn = void (*)(const std::uint16_t*, std::uint8_t*);

UnpackFn UnpackerOf(RawPacking packing) {
  switch (packing) {
    case RawPacking::kBits12BigEndian:
      return UnpackGroup12;
    case RawPacking::kBits10Illum:
      return UnpackGroup10;
    case RawPacking::kBits16LittleEndian:
      return UnpackGroup16;
  }
  throw Error("unknown raw packing");
}

PackFn PackerOf(RawPacking packing) {
  switch (packing) {
    case RawPacking::kBits12BigEndian:
      return PackGroup12;
    case RawPacking::kBits10Illum:
      return PackGroup10;
    case RawPacking::kBits16LittleEndian:
      return PackGroup16;
  }
  throw Error("unknown raw packing");
}

// The whole-group loop, specialised per packing so the compiler can inline the
// group function.
template <void (*Unpack)(const std::uint8_t*, std::uint16_t*)>
void UnpackFullGroups(const std::uint8_t* in, std::uint16_t* out, Index groups, Group g) {
#pragma omp parallel for schedule(static) if (groups > kParallelGroups)
  for (Index i = 0; i < groups; ++i) {
    Unpack(in + static_cast<std::size_t>(i) * g.bytes, out + static_cast<std::size_t>(i) * g.pixels);
  }
}

}  // namespace

std::string_view ToString(RawPacking packing) {
  switch (packing) {
    case RawPacking::kBits12BigEndian:
      return "12-bit big-endian";
    case RawPacking::kBits10Illum:
      return "10-bit Illum";
    case RawPacking::kBits16LittleEndian:
      return "16-bit little-endian";
  }
  return "unknown";
}

int BitsPerPixel(RawPacking packing) {
  switch (packing) {
    case RawPacking::kBits12BigEndian:
      return 12;
    case RawPacking::kBits10Illum:
      return 10;
    case RawPacking::kBits16LittleEndian:
      return 16;
  }
  throw Error("unknown raw packing");
}

std::uint16_t MaxPixelValue(RawPacking packing) {
  return static_cast<std::uint16_t>((1u << BitsPerPixel(packing)) - 1u);
}

std::size_t PackedByteCount(RawPacking packing, std::size_t pixel_count) {
  const Group g = GroupOf(packing);
  return (pixel_count + g.pixels - 1) / g.pixels * g.bytes;
}

void UnpackRaw(RawPacking packing, std::span<const std::uint8_t> packed, std::span<std::uint16_t> pixels,
               const std::string& source) {
  const std::size_t expected = PackedByteCount(packing, pixels.size());
  if (packed.size() != expected) {
    throw Error(source + ": raw buffer of " + std::to_string(packed.size()) + " bytes, expected " +
                std::to_string(expected) + " bytes for " + std::to_string(pixels.size()) + " pixels packed as " +
                std::string(ToString(packing)));
  }
  const Group g = GroupOf(packing);
  const std::size_t full_groups = pixels.size() / g.pixels;
  const Index groups = static_cast<Index>(full_groups);
  switch (packing) {
    case RawPacking::kBits12BigEndian:
      UnpackFullGroups<UnpackGroup12>(packed.data(), pixels.data(), groups, g);
      break;
    case RawPacking::kBits10Illum:
      UnpackFullGroups<UnpackGroup10>(packed.data(), pixels.data(), groups, g);
      break;
    case RawPacking::kBits16LittleEndian:
      UnpackFullGroups<UnpackGroup16>(packed.data(), pixels.data(), groups, g);
      break;
  }
  // The trailing partial group: unpack into a scratch group and keep only the
  // real pixels.
  const std::size_t rest = pixels.size() - full_groups * g.pixels;
  if (rest > 0) {
    std::uint16_t scratch[4] = {0, 0, 0, 0};
    UnpackerOf(packing)(packed.data() + full_groups * g.bytes, scratch);
    for (std::size_t i = 0; i < rest; ++i) pixels[full_groups * g.pixels + i] = scratch[i];
  }
}

std::vector<std::uint16_t> UnpackRaw(RawPacking packing, std::span<const std::uint8_t> packed, std::size_t pixel_count,
                                     const std::string& source) {
  // Check the size before allocating: a hostile pixel count must not allocate
  // gigabytes first.
  const std::size_t expected = PackedByteCount(packing, pixel_count);
  if (packed.size() != expected) {
    throw Error(source + ": raw buffer of " + std::to_string(packed.size()) + " bytes, expected " +
                std::to_string(expected) + " bytes for " + std::to_string(pixel_count) + " pixels packed as " +
                std::string(ToString(packing)));
  }
  std::vector<std::uint16_t> pixels(pixel_count);
  UnpackRaw(packing, packed, pixels, source);
  return pixels;
}

std::uint64_t SumPackedLevels(RawPacking packing, std::istream& in, std::size_t pixel_count,
                              const std::string& source) {
  // A multiple of every group's pixel count, so only the last block may end in a partial group; small enough to
  // stay in the cache and to unpack on one thread (below kParallelGroups).
  constexpr std::size_t kBlockPixels = std::size_t{1} << 16;
  std::vector<std::uint8_t> packed(PackedByteCount(packing, kBlockPixels));
  std::vector<std::uint16_t> pixels(kBlockPixels);
  std::uint64_t sum = 0;
  for (std::size_t done = 0; done < pixel_count;) {
    const std::size_t count = std::min(kBlockPixels, pixel_count - done);
    const std::size_t bytes = PackedByteCount(packing, count);
    in.read(reinterpret_cast<char*>(packed.data()), static_cast<std::streamsize>(bytes));
    if (static_cast<std::size_t>(in.gcount()) != bytes)
      throw Error(source + ": raw data ends after " +
                  std::to_string(PackedByteCount(packing, done) +
                                 static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0))) +
                  " bytes, expected " + std::to_string(PackedByteCount(packing, pixel_count)) + " bytes");
    UnpackRaw(packing, std::span<const std::uint8_t>(packed.data(), bytes),
              std::span<std::uint16_t>(pixels.data(), count), source);
    for (std::size_t i = 0; i < count; ++i) sum += pixels[i];
    done += count;
  }
  return sum;
}

std::vector<std::uint8_t> PackRaw(RawPacking packing, std::span<const std::uint16_t> pixels,
                                  const std::string& source) {
  const std::uint16_t max_value = MaxPixelValue(packing);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (pixels[i] > max_value) {
      throw Error(source + ": pixel " + std::to_string(i) + " has value " + std::to_string(pixels[i]) +
                  ", more than the " + std::to_string(BitsPerPixel(packing)) + "-bit maximum " +
                  std::to_string(max_value));
    }
  }
  const Group g = GroupOf(packing);
  std::vector<std::uint8_t> packed(PackedByteCount(packing, pixels.size()));
  const std::size_t full_groups = pixels.size() / g.pixels;
  const PackFn pack = PackerOf(packing);
  const Index groups = static_cast<Index>(full_groups);
#pragma omp parallel for schedule(static) if (groups > kParallelGroups)
  for (Index i = 0; i < groups; ++i) {
    pack(pixels.data() + static_cast<std::size_t>(i) * g.pixels, packed.data() + static_cast<std::size_t>(i) * g.bytes);
  }
  const std::size_t rest = pixels.size() - full_groups * g.pixels;
  if (rest > 0) {
    std::uint16_t scratch[4] = {0, 0, 0, 0};  // missing pixels of the last group are packed as 0
    for (std::size_t i = 0; i < rest; ++i) scratch[i] = pixels[full_groups * g.pixels + i];
    pack(scratch, packed.data() + full_groups * g.bytes);
  }
  return packed;
}

RawImage UnpackRawImage(RawPacking packing, std::span<const std::uint8_t> packed, int width, int height,
                        const std::string& source) {
  if (width <= 0 || height <= 0) {
    throw Error(source + ": raw image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is not positive");
  }
  RawImage image;
  image.width = width;
  image.height = height;
  image.pixels = UnpackRaw(packing, packed, image.PixelCount(), source);
  return image;
}

}  // namespace lfsp::decode
