// Unit tests of segment/src/label_block.h: the 3x3 label patterns the refinement reads instead of comparing labels
// one by one. Each table is checked against a direct computation over every pattern it can be asked about.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "label_block.h"

namespace lfsp::segment {
namespace {

constexpr std::array<std::array<int, 2>, 8> kRingCells = {
    {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};  // (column, row), clockwise

unsigned BitOf(int column, int row) { return 1u << (4 * row + column); }

// The number of 4-connected pieces the ring's cells of the label make once the centre is gone, counting a corner
// cell only when one of its two edge cells is in (a lone corner touches the centre diagonally only, so it was never
// joined to the slice through the ring).
int PiecesWithoutCentre(unsigned pattern) {
  bool in[3][3] = {};
  for (const auto& cell : kRingCells) in[cell[1]][cell[0]] = (pattern & BitOf(cell[0], cell[1])) != 0;
  for (int row : {0, 2}) {
    for (int column : {0, 2}) {
      if (in[row][column] && !in[row][1] && !in[1][column]) in[row][column] = false;
    }
  }
  int pieces = 0;
  bool seen[3][3] = {};
  for (const auto& start : kRingCells) {
    if (!in[start[1]][start[0]] || seen[start[1]][start[0]]) continue;
    ++pieces;
    std::vector<std::array<int, 2>> stack = {start};
    seen[start[1]][start[0]] = true;
    while (!stack.empty()) {
      const auto [column, row] = stack.back();
      stack.pop_back();
      const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (const auto& step : steps) {
        const int c = column + step[0], r = row + step[1];
        if (c < 0 || r < 0 || c > 2 || r > 2 || (c == 1 && r == 1) || !in[r][c] || seen[r][c]) continue;
        seen[r][c] = true;
        stack.push_back({c, r});
      }
    }
  }
  return pieces;
}

TEST(LabelBlock, SplitsWithoutCentreIsTrueExactlyWhenTheRingFallsIntoSeveralPieces) {
  int splitting = 0;
  for (unsigned ring = 0; ring < 256; ++ring) {
    unsigned pattern = 0;
    for (int i = 0; i < 8; ++i) {
      if ((ring >> i) & 1u)
        pattern |= BitOf(kRingCells[static_cast<std::size_t>(i)][0], kRingCells[static_cast<std::size_t>(i)][1]);
    }
    const bool expected = PiecesWithoutCentre(pattern) > 1;
    EXPECT_EQ(SplitsWithoutCentre(pattern), expected) << "ring pattern " << ring;
    EXPECT_EQ(SplitsWithoutCentre(pattern | BitOf(1, 1) | 0x888u), expected) << "centre and padding bits ignored";
    splitting += expected;
  }
  EXPECT_GT(splitting, 50);   // e.g. left and right in, top and bottom out
  EXPECT_LT(splitting, 200);  // e.g. a full ring does not split
}

TEST(LabelBlock, RingCountCountsTheEightNeighboursOnly) {
  for (unsigned pattern = 0; pattern < 4096; ++pattern) {
    int expected = 0;
    for (const auto& cell : kRingCells) expected += (pattern & BitOf(cell[0], cell[1])) != 0;
    EXPECT_EQ(RingCount(pattern), expected) << "pattern " << pattern;
  }
}

TEST(LabelBlock, SameAs3x3MarksTheBlocksLabelsEqualToTheKey) {
  constexpr int kWidth = 7, kHeight = 5;
  std::mt19937 random(7);
  std::vector<std::int32_t> labels(kWidth * kHeight + 1);  // + 1: the last row's extra label SameAs3x3 may read
  for (auto& label : labels) label = static_cast<std::int32_t>(random() % 3);
  for (int y = 1; y + 1 < kHeight; ++y) {
    for (int x = 1; x + 1 < kWidth; ++x) {
      for (std::int32_t key = 0; key < 3; ++key) {
        unsigned expected = 0;
        for (int row = 0; row < 3; ++row) {
          for (int column = 0; column < 3; ++column) {
            if (labels[static_cast<std::size_t>((y + row - 1) * kWidth + x + column - 1)] == key)
              expected |= BitOf(column, row);
          }
        }
        const unsigned same = SameAs3x3(&labels[static_cast<std::size_t>(y * kWidth + x)], kWidth, key);
        EXPECT_EQ(same & ~0x888u, expected);  // bits 3, 7 and 11 lie outside the block: unspecified
      }
    }
  }
}

}  // namespace
}  // namespace lfsp::segment
