#include "connectivity.h"

#include <algorithm>
#include <map>
#include <unordered_map>
#include <utility>
#include <vector>

namespace lfsp::segment {
namespace {

// The 4-connected pieces of a label map: each pixel's piece, and each piece's label, size and pixels (grouped in
// `order`, piece k at order[start[k] .. start[k + 1])).
struct Pieces {
  std::vector<int> of_pixel;
  std::vector<std::int32_t> label;
  std::vector<int> size;
  std::vector<int> order;
  std::vector<int> start;
};

// Calls visit(j) for each 4-neighbour j of pixel `index`.
template <typename Visit>
void ForEachNeighbour(int index, int width, int height, Visit visit) {
  const int x = index % width, y = index / width;
  if (x > 0) visit(index - 1);
  if (x + 1 < width) visit(index + 1);
  if (y > 0) visit(index - width);
  if (y + 1 < height) visit(index + width);
}

Pieces FindPieces(const std::int32_t* labels, int width, int height) {
  const int pixels = width * height;
  Pieces pieces;
  pieces.of_pixel.assign(static_cast<std::size_t>(pixels), -1);
  pieces.order.reserve(static_cast<std::size_t>(pixels));
  for (int seed = 0; seed < pixels; ++seed) {
    if (pieces.of_pixel[static_cast<std::size_t>(seed)] >= 0) continue;
    const int id = static_cast<int>(pieces.size.size());
    const std::int32_t label = labels[seed];
    const std::size_t start = pieces.order.size();
    pieces.start.push_back(static_cast<int>(start));
    pieces.of_pixel[static_cast<std::size_t>(seed)] = id;
    pieces.order.push_back(seed);
    for (std::size_t head = start; head < pieces.order.size(); ++head) {  // breadth-first flood fill
      ForEachNeighbour(pieces.order[head], width, height, [&](int j) {
        if (pieces.of_pixel[static_cast<std::size_t>(j)] >= 0 || labels[j] != label) return;
        pieces.of_pixel[static_cast<std::size_t>(j)] = id;
        pieces.order.push_back(j);
      });
    }
    pieces.size.push_back(static_cast<int>(pieces.order.size() - start));
    pieces.label.push_back(label);
  }
  pieces.start.push_back(static_cast<int>(pieces.order.size()));
  return pieces;
}

}  // namespace

long long KeepLargestPieces(std::int32_t* labels, int width, int height) {
  const Pieces pieces = FindPieces(labels, width, height);
  const int count = static_cast<int>(pieces.size.size());

  // Each label's largest piece (the first found among equals) is settled and keeps its label.
  std::unordered_map<std::int32_t, int> largest;
  for (int id = 0; id < count; ++id) {
    auto [it, inserted] = largest.try_emplace(pieces.label[static_cast<std::size_t>(id)], id);
    if (!inserted && pieces.size[static_cast<std::size_t>(id)] > pieces.size[static_cast<std::size_t>(it->second)])
      it->second = id;
  }
  if (largest.size() == pieces.size.size()) return 0;  // every label is one piece already

  std::vector<char> settled(static_cast<std::size_t>(count), 0);
  std::vector<std::int32_t> settled_label(pieces.label);
  std::vector<int> stray;
  for (int id = 0; id < count; ++id) {
    if (largest[pieces.label[static_cast<std::size_t>(id)]] == id)
      settled[static_cast<std::size_t>(id)] = 1;
    else
      stray.push_back(id);
  }

  // A stray piece joins the label it shares most border with, counting only neighbours that are settled, and then is
  // settled itself. Joining only settled regions keeps every label one connected region: merging into a piece that
  // moved later used to strand the joiner as an island. A piece with no settled neighbour yet waits for a later
  // round; every round finishes at least one piece, since the image is connected and holds settled pieces.
  long long relabelled = 0;
  while (!stray.empty()) {
    std::vector<int> waiting;
    for (const int id : stray) {
      const auto sid = static_cast<std::size_t>(id);
      std::map<std::int32_t, int> votes;  // ordered: ties go to the smaller label, the same on every run
      for (int i = pieces.start[sid]; i < pieces.start[sid + 1]; ++i) {
        ForEachNeighbour(pieces.order[static_cast<std::size_t>(i)], width, height, [&](int j) {
          const auto neighbour = static_cast<std::size_t>(pieces.of_pixel[static_cast<std::size_t>(j)]);
          if (neighbour != sid && settled[neighbour]) ++votes[settled_label[neighbour]];
        });
      }
      if (votes.empty()) {
        waiting.push_back(id);
        continue;
      }
      const auto best = std::max_element(votes.begin(), votes.end(),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
      settled_label[sid] = best->first;
      settled[sid] = 1;
      if (best->first != pieces.label[sid]) relabelled += pieces.size[sid];
    }
    if (waiting.size() == stray.size()) break;  // no settled piece anywhere (cannot happen: each label keeps one)
    stray = std::move(waiting);
  }
  for (int id = 0; id < count; ++id) {
    const auto sid = static_cast<std::size_t>(id);
    if (settled_label[sid] == pieces.label[sid]) continue;
    for (int i = pieces.start[sid]; i < pieces.start[sid + 1]; ++i)
      labels[pieces.order[static_cast<std::size_t>(i)]] = settled_label[sid];
  }
  return relabelled;
}

}  // namespace lfsp::segment
