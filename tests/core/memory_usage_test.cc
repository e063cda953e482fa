// core/memory_usage.h: DiscardPages gives back the pages of a live allocation, which then read as zero, and leaves
// the bytes around them alone (issue 46: the slicing discards the demosaicked image behind itself).

#include "lfsp/core/memory_usage.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace lfsp {
namespace {

TEST(MemoryUsage, DiscardedPagesGoBackAndReadAsZero) {
#ifndef __linux__
  GTEST_SKIP() << "DiscardPages does nothing here";
#endif
  constexpr std::size_t kBytes = std::size_t{256} << 20;  // 256 MB, so the drop stands out of the process's noise
  std::vector<std::uint8_t> buffer(kBytes, 7);            // every page touched
  const double before = ResidentMegabytes();
  // Not page-aligned on purpose: the partial pages at both ends must keep their bytes.
  const std::size_t from = 12345, to = kBytes - 54321;
  DiscardPages(buffer.data() + from, buffer.data() + to);
  const double after = ResidentMegabytes();
  EXPECT_GT(before - after, 240.0) << "resident " << before << " -> " << after << " MB";
  EXPECT_EQ(buffer[from - 1], 7);
  EXPECT_EQ(buffer[from], 7);    // in the first partial page: kept
  EXPECT_EQ(buffer[to - 1], 7);  // in the last partial page: kept
  EXPECT_EQ(buffer[to], 7);
  EXPECT_EQ(buffer[kBytes / 2], 0);  // discarded
  // Only the bytes outside the range and in the two partial pages keep their 7s.
  EXPECT_LE(static_cast<std::size_t>(std::count(buffer.begin(), buffer.end(), std::uint8_t{7})),
            from + (kBytes - to) + 2 * 4096);
  // Reusable and freed as usual.
  std::fill(buffer.begin(), buffer.end(), std::uint8_t{3});
  EXPECT_EQ(buffer[kBytes / 2], 3);
}

TEST(MemoryUsage, NothingToDiscardWithinOnePage) {
  std::vector<std::uint8_t> buffer(100, 5);
  DiscardPages(buffer.data() + 10, buffer.data() + 90);
  EXPECT_EQ(std::count(buffer.begin(), buffer.end(), std::uint8_t{5}), 100);
  DiscardPages(buffer.data() + 90, buffer.data() + 10);  // an empty range
  EXPECT_EQ(std::count(buffer.begin(), buffer.end(), std::uint8_t{5}), 100);
}

}  // namespace
}  // namespace lfsp
