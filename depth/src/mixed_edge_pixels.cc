#include "lfsp/depth/mixed_edge_pixels.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "lfsp/core/error.h"

namespace lfsp::depth {
namespace {

using Colour = std::array<float, 3>;

float Dot(const Colour& a, const Colour& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Colour Minus(const Colour& a, const Colour& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

// RGB over its sum (held at 1e-3 only so that black does not divide by zero). Near black the chromaticity is mostly
// noise; since both shares must be under the bound, that noise can keep a pixel from moving but cannot move one that
// the RGB share would keep.
Colour Chromaticity(const Colour& c) {
  const float sum = std::max(c[0] + c[1] + c[2], 1e-3f);
  return {c[0] / sum, c[1] / sum, c[2] / sum};
}

// Where `colour` lies on the way from `far` (0) to `near` (1), or nothing when the two are closer than `separation`.
std::optional<float> ShareOfNear(const Colour& colour, const Colour& near, const Colour& far, float separation) {
  const Colour span = Minus(near, far);
  const float squared = Dot(span, span);
  if (!(std::sqrt(squared) > separation)) return std::nullopt;
  return Dot(Minus(colour, far), span) / squared;
}

// One round, along one direction (dy, dx) from p to its farther neighbour q: writes the moves into `moved` (read
// from `disparity`, the round's start) and returns their number.
int ReassignAlong(const DisparityMap& disparity, const cv::Mat& guide, int dy, int dx, const MixedEdgeOptions& options,
                  DisparityMap& moved) {
  const int width = disparity.width(), height = disparity.height();
  const auto inside = [&](int y, int x) { return y >= 0 && x >= 0 && y < height && x < width; };
  const auto colour = [&](int y, int x) {
    const cv::Vec3f& c = guide.at<cv::Vec3f>(y, x);
    return Colour{c[0], c[1], c[2]};
  };
  int moves = 0;
#pragma omp parallel for schedule(static) reduction(+ : moves)
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!inside(y + dy, x + dx)) continue;
      const float near = disparity.at(y, x), far = disparity.at(y + dy, x + dx);
      if (!(near - far > options.jump)) continue;  // also false when either is not finite
      // Each side's colour, from `depth` pixels that are even with it in disparity.
      Colour near_colour{0, 0, 0}, far_colour{0, 0, 0};
      bool even = true;
      for (int k = 1; k <= options.depth && even; ++k) {
        const int ny = y - k * dy, nx = x - k * dx, fy = y + (k + 1) * dy, fx = x + (k + 1) * dx;
        even = inside(ny, nx) && inside(fy, fx) && std::abs(disparity.at(ny, nx) - near) < options.jump &&
               std::abs(disparity.at(fy, fx) - far) < options.jump;
        if (!even) break;
        const Colour n = colour(ny, nx), f = colour(fy, fx);
        for (int c = 0; c < 3; ++c) {
          near_colour[static_cast<std::size_t>(c)] += n[static_cast<std::size_t>(c)];
          far_colour[static_cast<std::size_t>(c)] += f[static_cast<std::size_t>(c)];
        }
      }
      if (!even) continue;
      for (int c = 0; c < 3; ++c) {
        near_colour[static_cast<std::size_t>(c)] /= static_cast<float>(options.depth);
        far_colour[static_cast<std::size_t>(c)] /= static_cast<float>(options.depth);
      }
      const Colour own = colour(y, x);
      const std::optional<float> rgb_share = ShareOfNear(own, near_colour, far_colour, options.rgb_separation);
      if (!rgb_share) continue;
      const std::optional<float> chroma_share = ShareOfNear(Chromaticity(own), Chromaticity(near_colour),
                                                            Chromaticity(far_colour), options.chroma_separation);
      if (!chroma_share) continue;
      if (!(std::max(*rgb_share, *chroma_share) < options.max_share)) continue;
      moved.at(y, x) = far;
      ++moves;
    }
  }
  return moves;
}

}  // namespace

int ReassignMixedEdgePixels(DisparityMap& disparity, const cv::Mat& guide_rgb, const MixedEdgeOptions& options) {
  if (!(options.max_share > 0.0f) || options.rounds <= 0) return 0;
  if (guide_rgb.type() != CV_32FC3 || guide_rgb.rows != disparity.height() || guide_rgb.cols != disparity.width())
    throw Error("mixed edge pixels: the guide must be a float RGB image of the disparity map's size");
  if (options.depth < 1) throw Error("mixed edge pixels: the sides' depth must be at least 1 pixel");
  int total = 0;
  for (int round = 0; round < options.rounds; ++round) {
    DisparityMap next = disparity;
    int moves = 0;
    // Every direction reads the round's start; where a pixel moves along several, the last one's farther side wins.
    for (const auto& [dy, dx] : {std::pair{0, 1}, std::pair{0, -1}, std::pair{1, 0}, std::pair{-1, 0}})
      moves += ReassignAlong(disparity, guide_rgb, dy, dx, options, next);
    disparity = std::move(next);
    total += moves;
    if (moves == 0) break;
  }
  return total;
}

}  // namespace lfsp::depth
