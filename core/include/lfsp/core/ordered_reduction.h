#pragma once
// A parallel sum whose result does not depend on the thread count or on how the threads were scheduled.
//
// Floating-point addition is not associative: per-thread partial sums merged in whatever order the threads finish
// (or over whatever items a dynamic schedule happened to give each thread) round differently from run to run. That
// made refocused images and capture-derived white images differ in their last bits between two identical runs, and
// `lfsp pipeline` then no longer wrote the bytes the single commands write. Here the items are cut into a fixed
// number of contiguous blocks, each block is summed in item order into its own partial, and the partials are folded
// in block order: the same additions in the same order on every machine.

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace lfsp {

// The default number of blocks: enough to keep two (or a few more) cores busy when blocks differ in cost, few
// enough that one partial per block stays cheap to hold and to fold.
inline constexpr int kOrderedReductionBlocks = 8;

// Sums items [0, count): `make_partial()` creates an empty partial, `add_item(item, partial)` adds one item to it,
// and `merge(into, from)` adds one partial to another. Returns the folded partial (an empty one when count <= 0).
// `add_item` runs concurrently on different partials, so it must only write to the partial it is given.
template <typename MakePartial, typename AddItem, typename Merge>
auto OrderedParallelSum(int count, MakePartial make_partial, AddItem add_item, Merge merge,
                        int blocks = kOrderedReductionBlocks) {
  using Partial = decltype(make_partial());
  blocks = std::clamp(blocks, 1, std::max(1, count));
  std::vector<Partial> partials;
  partials.reserve(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b) partials.push_back(make_partial());
  if (count > 0) {
#pragma omp parallel for schedule(dynamic, 1)
    for (int b = 0; b < blocks; ++b) {
      // Block b holds items [count * b / blocks, count * (b + 1) / blocks).
      const long long begin = static_cast<long long>(count) * b / blocks;
      const long long end = static_cast<long long>(count) * (b + 1) / blocks;
      for (long long item = begin; item < end; ++item)
        add_item(static_cast<int>(item), partials[static_cast<std::size_t>(b)]);
    }
  }
  for (int b = 1; b < blocks; ++b) merge(partials.front(), partials[static_cast<std::size_t>(b)]);
  return std::move(partials.front());
}

}  // namespace lfsp
