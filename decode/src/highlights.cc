#include "highlights.h"

#include <algorithm>
#include <limits>

#include "bayer_levels.h"
#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

// Colour (0 R, 1 G, 2 B) of each Bayer phase (BayerPhase): Lytro's channels r, gr, gb, b.
std::array<int, 4> PhaseColours(BayerPattern pattern) {
  const std::array<int, 4> channels = TileChannels(pattern);
  std::array<int, 4> colours{};
  for (int phase = 0; phase < 4; ++phase) {
    const int channel = channels[static_cast<std::size_t>(phase)];
    colours[static_cast<std::size_t>(phase)] = channel == 0 ? 0 : channel == 3 ? 2 : 1;
  }
  return colours;
}

// Each colour's mean of `inverse_white` over its sites in the 3 x 3 neighbourhood of (x, y), clamped to the image.
std::array<float, 3> Ceilings(const cv::Mat& inverse_white, const std::array<int, 4>& colours, int x, int y) {
  float sum[3] = {0, 0, 0};
  int count[3] = {0, 0, 0};
  for (int j = std::max(0, y - 1); j <= std::min(inverse_white.rows - 1, y + 1); ++j) {
    const float* row = inverse_white.ptr<float>(j);
    for (int i = std::max(0, x - 1); i <= std::min(inverse_white.cols - 1, x + 1); ++i) {
      const int colour = colours[static_cast<std::size_t>(BayerPhase(i, j))];
      sum[colour] += row[i];
      ++count[colour];
    }
  }
  std::array<float, 3> ceilings{};
  for (int c = 0; c < 3; ++c) ceilings[static_cast<std::size_t>(c)] = count[c] > 0 ? sum[c] / count[c] : 0.0f;
  return ceilings;
}

}  // namespace

long NeutraliseClippedHighlights(cv::Mat& rgb, const cv::Mat& inverse_white, BayerPattern pattern,
                                 const std::array<double, 3>& gains, float clipped_fraction) {
  if (rgb.type() != CV_32FC3 || inverse_white.type() != CV_32FC1 || rgb.size() != inverse_white.size())
    throw Error("decode: the white image must match the demosaiced image to find its clipped highlights");
  const std::array<int, 4> colours = PhaseColours(pattern);
  const float gain[3] = {static_cast<float>(gains[0]), static_cast<float>(gains[1]), static_cast<float>(gains[2])};
  constexpr float kNone = std::numeric_limits<float>::infinity();
  long changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed)
  for (int y = 0; y < rgb.rows; ++y) {
    float* pixel = rgb.ptr<float>(y);
    for (int x = 0; x < rgb.cols; ++x, pixel += 3) {
      const std::array<float, 3> ceiling = Ceilings(inverse_white, colours, x, y);
      float level = kNone;  // white-balanced
      for (int c = 0; c < 3; ++c)
        if (ceiling[c] > 0.0f && pixel[c] >= clipped_fraction * ceiling[c])
          level = std::min(level, ceiling[c] * gain[c]);
      if (level == kNone) continue;
      bool limited = false;
      for (int c = 0; c < 3; ++c) {
        const float limit = level / gain[c];
        if (pixel[c] > limit) {
          pixel[c] = limit;
          limited = true;
        }
      }
      if (limited) ++changed;
    }
  }
  return changed;
}

}  // namespace lfsp::decode
