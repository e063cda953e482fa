#pragma once

#include <array>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

// The 3x3 block of labels around a ray, as a bit pattern, and what the refinement asks of it: how many of the 8
// ring neighbours share the label, and whether the label's slice would split without the centre.
namespace lfsp::segment {

// Bit (4 row + column) set where the label of the 3x3 block centred on c equals k (bits 3, 7 and 11 are not part
// of the block and may be set either way). With SSE2 each row is one 4-lane compare, which reads one label past the
// block: callers keep c + stride + 2 inside the buffer.
inline unsigned SameAs3x3(const std::int32_t* c, int stride, std::int32_t k) {
#if defined(__SSE2__)
  const __m128i key = _mm_set1_epi32(k);
  unsigned same = 0;
  for (int row = 0; row < 3; ++row) {
    const __m128i labels = _mm_loadu_si128(reinterpret_cast<const __m128i*>(c + (row - 1) * stride - 1));
    same |= static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(labels, key)))) << (4 * row);
  }
  return same;
#else
  unsigned same = 0;
  for (int row = 0; row < 3; ++row) {
    const std::int32_t* r = c + (row - 1) * stride;
    same |= (static_cast<unsigned>(r[-1] == k) | static_cast<unsigned>(r[0] == k) << 1 |
             static_cast<unsigned>(r[1] == k) << 2)
            << (4 * row);
  }
  return same;
#endif
}

// The ring of a SameAs3x3 pattern (the block without its centre, bit 5).
inline constexpr unsigned kRingBits = 0x757u;
// The 4-neighbours: up, left, right, down.
inline constexpr unsigned kEdgeBits = 0x252u;

namespace detail {

// Bits of the ring in order around the centre, starting top-left and going clockwise.
inline constexpr std::array<int, 8> kRingOrder = {0, 1, 2, 6, 10, 9, 8, 4};

constexpr bool SplitsWithoutCentre(unsigned pattern) {
  bool in[8] = {};
  for (int i = 0; i < 8; ++i) in[i] = ((pattern >> kRingOrder[static_cast<std::size_t>(i)]) & 1u) != 0;
  for (int i = 0; i < 8; i += 2) {  // corners count only when 4-connected to the ring through an edge neighbour
    if (in[i] && !in[(i + 7) % 8] && !in[(i + 1) % 8]) in[i] = false;
  }
  int runs = 0;
  for (int i = 0; i < 8; ++i) {
    if (in[i] && !in[(i + 7) % 8]) ++runs;
  }
  return runs > 1;
}

template <typename Value, typename Rule>
constexpr std::array<Value, kRingBits + 1> RingTable(Rule rule) {
  std::array<Value, kRingBits + 1> table{};
  for (unsigned pattern = 0; pattern <= kRingBits; ++pattern) table[pattern] = rule(pattern & kRingBits);
  return table;
}

inline constexpr auto kRingCounts = RingTable<std::uint8_t>([](unsigned pattern) {
  int count = 0;
  for (int bit : kRingOrder) count += (pattern >> bit) & 1u;
  return static_cast<std::uint8_t>(count);
});
inline constexpr auto kSplits = RingTable<bool>(SplitsWithoutCentre);

}  // namespace detail

// How many of the 8 ring neighbours share the label (a table: without -mpopcnt, std::popcount is a library call).
inline int RingCount(unsigned same) { return detail::kRingCounts[same & kRingBits]; }

// Would removing the centre split its label's slice? True if the label appears in more than one separate run
// around the ring (corners count only when 4-connected to the ring through an edge neighbour).
inline bool SplitsWithoutCentre(unsigned same) { return detail::kSplits[same & kRingBits]; }

}  // namespace lfsp::segment
