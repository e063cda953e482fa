// Fuzz target: the raw unpackers. Input: byte 0 picks the packing, bytes 1-2 the pixel count (little-endian), the
// rest is the packed buffer. A buffer of the wrong size must give lfsp::Error; a right-sized one must unpack,
// and packing the pixels again must give back the same bytes (the layouts are bijections on whole groups).

#include <cstdlib>
#include <span>

#include "fuzz_target.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/raw_packing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using lfsp::decode::RawPacking;
  if (size < 3) return 0;
  constexpr RawPacking kPackings[] = {RawPacking::kBits12BigEndian, RawPacking::kBits10Illum,
                                      RawPacking::kBits16LittleEndian};
  const RawPacking packing = kPackings[data[0] % 3];
  const std::size_t pixel_count = static_cast<std::size_t>(data[1]) | (static_cast<std::size_t>(data[2]) << 8);
  const std::span<const std::uint8_t> packed(data + 3, size - 3);
  const bool right_size = packed.size() == lfsp::decode::PackedByteCount(packing, pixel_count);
  try {
    const auto pixels = lfsp::decode::UnpackRaw(packing, packed, pixel_count, "fuzz.raw");
    if (!right_size) std::abort();  // a wrong-sized buffer was accepted
    for (const std::uint16_t p : pixels) {
      if (p > lfsp::decode::MaxPixelValue(packing)) std::abort();
    }
    const std::size_t group = packing == RawPacking::kBits12BigEndian ? 2 : packing == RawPacking::kBits10Illum ? 4 : 1;
    if (pixel_count % group == 0) {
      const auto again = lfsp::decode::PackRaw(packing, pixels, "fuzz.raw");
      if (!std::equal(again.begin(), again.end(), packed.begin(), packed.end())) std::abort();
    }
  } catch (const lfsp::Error&) {
    if (right_size) std::abort();  // a right-sized buffer was refused
  }
  return 0;
}
