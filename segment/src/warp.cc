#include "warp.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <utility>

#include "lfsp/core/rounding.h"

namespace lfsp::segment {

void ForwardWarp(const std::int32_t* centre_labels, const float* centre_disparity, int width, int height, int du,
                 int dv, std::int32_t* view_labels, float* view_depth) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::fill(view_labels, view_labels + pixels, -1);
  std::fill(view_depth, view_depth + pixels, -std::numeric_limits<float>::infinity());
  for (int y0 = 0; y0 < height; ++y0) {
    for (int x0 = 0; x0 < width; ++x0) {
      const std::size_t source =
          static_cast<std::size_t>(y0) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x0);
      const float d = centre_disparity[source];
      if (centre_labels[source] < 0 || !std::isfinite(d)) continue;
      // The target is the nearest pixel, floor(position + 0.5). Compared as floats first: a hostile disparity (1e30)
      // lands beyond what an int holds. floor(v) >= 0 exactly when v >= 0, and floor(v) < width exactly when
      // v < width (width being whole); inside those bounds truncation is the floor. So no floor call, which without
      // SSE4.1 was half this loop's time.
      const float fx = static_cast<float>(x0) - static_cast<float>(du) * d + 0.5f;
      const float fy = static_cast<float>(y0) - static_cast<float>(dv) * d + 0.5f;
      if (!(fx >= 0.0f && fy >= 0.0f && fx < static_cast<float>(width) && fy < static_cast<float>(height))) continue;
      const int x = static_cast<int>(fx), y = static_cast<int>(fy);
      const std::size_t target =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      if (d > view_depth[target]) {
        view_depth[target] = d;
        view_labels[target] = centre_labels[source];
      }
    }
  }
}

namespace {

// Breadth-first propagation of labels (and depths) into the remaining holes: each takes a nearest labelled pixel.
void FillNearest(std::int32_t* labels, float* depth, int width, int height) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<int> queue;
  bool any_hole = false;
  for (std::size_t i = 0; i < pixels && !any_hole; ++i) any_hole = labels[i] < 0;
  if (!any_hole) return;
  // Seeds: labelled pixels with a hole among their 4-neighbours.
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int i = y * width + x;
      if (labels[i] < 0) continue;
      const bool next_to_hole = (x > 0 && labels[i - 1] < 0) || (x + 1 < width && labels[i + 1] < 0) ||
                                (y > 0 && labels[i - width] < 0) || (y + 1 < height && labels[i + width] < 0);
      if (next_to_hole) queue.push_back(i);
    }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int index = queue[head];
    const int x = index % width, y = index / width;
    const int neighbours[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
    for (const auto& n : neighbours) {
      if (n[0] < 0 || n[1] < 0 || n[0] >= width || n[1] >= height) continue;
      const int j = n[1] * width + n[0];
      if (labels[j] >= 0) continue;
      labels[j] = labels[index];
      depth[j] = depth[index];
      queue.push_back(j);
    }
  }
}

}  // namespace

int FillReach(float max_abs, int du, int dv) {
  const float reach = std::ceil(2.0f * max_abs * static_cast<float>(std::max(std::abs(du), std::abs(dv)))) + 2.0f;
  return reach < 512.0f ? static_cast<int>(reach) : 512;  // NaN (0 x infinity) is not below 512 either
}

void FillHoles(std::int32_t* view_labels, float* view_depth, int width, int height, int du, int dv, int max_steps) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const int step = std::max(std::abs(du), std::abs(dv));
  bool any_hole = false;
  for (std::size_t i = 0; i < pixels && !any_hole; ++i) any_hole = view_labels[i] < 0;
  if (!any_hole) return;
  if (step > 0) {
    // Unit steps along the epipolar direction (du, dv).
    const double sx = static_cast<double>(du) / step, sy = static_cast<double>(dv) / step;
    // Fills are collected and applied afterwards so the result does not depend on the scan order.
    std::vector<std::pair<std::size_t, int>> fills;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t index =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
        if (view_labels[index] >= 0) continue;
        int best = -1;
        for (int direction : {1, -1}) {
          for (int k = 1; k <= max_steps; ++k) {
            const int nx = RoundHalfAway(x + direction * k * sx);
            const int ny = RoundHalfAway(y + direction * k * sy);
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) break;
            const int j = ny * width + nx;
            if (view_labels[j] < 0) continue;
            if (best < 0 || view_depth[j] < view_depth[best]) best = j;
            break;
          }
        }
        if (best >= 0) fills.emplace_back(index, best);
      }
    }
    for (const auto& [index, source] : fills) {
      view_labels[index] = view_labels[source];
      view_depth[index] = view_depth[source];
    }
  }
  FillNearest(view_labels, view_depth, width, height);
}

}  // namespace lfsp::segment
