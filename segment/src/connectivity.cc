#include "connectivity.h"

#include <algorithm>
#include <unordered_map>
#include <vector>

namespace lfsp::segment {

long long KeepLargestPieces(std::int32_t* labels, int width, int height) {
  const int pixels = width * height;
  std::vector<int> piece(static_cast<std::size_t>(pixels), -1);
  std::vector<int> piece_size;
  std::vector<std::int32_t> piece_label;
  std::vector<int> order;  // pixels grouped by piece, in breadth-first order
  std::vector<int> piece_start;
  order.reserve(static_cast<std::size_t>(pixels));
  for (int seed = 0; seed < pixels; ++seed) {
    if (piece[static_cast<std::size_t>(seed)] >= 0) continue;
    const int id = static_cast<int>(piece_size.size());
    const std::int32_t label = labels[seed];
    const std::size_t start = order.size();
    piece_start.push_back(static_cast<int>(start));
    piece[static_cast<std::size_t>(seed)] = id;
    order.push_back(seed);
    for (std::size_t head = start; head < order.size(); ++head) {
      const int index = order[head];
      const int x = index % width, y = index / width;
      const int neighbours[4] = {x > 0 ? index - 1 : -1, x + 1 < width ? index + 1 : -1, y > 0 ? index - width : -1,
                                 y + 1 < height ? index + width : -1};
      for (int j : neighbours) {
        if (j < 0 || piece[static_cast<std::size_t>(j)] >= 0 || labels[j] != label) continue;
        piece[static_cast<std::size_t>(j)] = id;
        order.push_back(j);
      }
    }
    piece_size.push_back(static_cast<int>(order.size() - start));
    piece_label.push_back(label);
  }
  piece_start.push_back(static_cast<int>(order.size()));

  std::unordered_map<std::int32_t, int> largest;  // label -> its largest piece, for labels in several pieces
  if (piece_size.size() == [&] {
        std::unordered_map<std::int32_t, int> seen;
        for (std::int32_t label : piece_label) ++seen[label];
        return seen.size();
      }()) {
    return 0;  // every label is one piece already
  }
  for (int id = 0; id < static_cast<int>(piece_size.size()); ++id) {
    auto [it, inserted] = largest.try_emplace(piece_label[static_cast<std::size_t>(id)], id);
    if (!inserted && piece_size[static_cast<std::size_t>(id)] > piece_size[static_cast<std::size_t>(it->second)]) {
      it->second = id;
    }
  }
  long long relabelled = 0;
  for (int id = 0; id < static_cast<int>(piece_size.size()); ++id) {
    const std::size_t sid = static_cast<std::size_t>(id);
    if (largest[piece_label[sid]] == id) continue;
    std::unordered_map<std::int32_t, int> votes;
    for (int i = piece_start[sid]; i < piece_start[sid + 1]; ++i) {
      const int index = order[static_cast<std::size_t>(i)];
      const int x = index % width, y = index / width;
      const int neighbours[4] = {x > 0 ? index - 1 : -1, x + 1 < width ? index + 1 : -1, y > 0 ? index - width : -1,
                                 y + 1 < height ? index + width : -1};
      for (int j : neighbours) {
        if (j >= 0 && piece[static_cast<std::size_t>(j)] != id) ++votes[labels[j]];
      }
    }
    std::int32_t target = piece_label[sid];
    int most = 0;
    for (const auto& [label, count] : votes) {
      if (count > most) {
        most = count;
        target = label;
      }
    }
    if (most == 0) continue;  // the piece fills the view
    for (int i = piece_start[sid]; i < piece_start[sid + 1]; ++i) labels[order[static_cast<std::size_t>(i)]] = target;
    relabelled += piece_size[sid];
  }
  return relabelled;
}

}  // namespace lfsp::segment
