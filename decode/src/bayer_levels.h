#pragma once

#include <array>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/decode/lytro_metadata.h"

namespace lfsp::decode {

// Bayer phase of pixel (x, y): 2 * (y & 1) + (x & 1), the index into a 2x2 tile read row by row.
inline int BayerPhase(int x, int y) { return 2 * (y & 1) + (x & 1); }

// Which Lytro Bayer channel (0 r, 1 gr, 2 gb, 3 b) sits at each phase of the tile.
inline std::array<int, 4> TileChannels(BayerPattern pattern) {
  switch (pattern) {
    case BayerPattern::kRGGB:
      return {0, 1, 2, 3};
    case BayerPattern::kGRBG:
      return {1, 0, 3, 2};
    case BayerPattern::kGBRG:
      return {2, 3, 0, 1};
    case BayerPattern::kBGGR:
      return {3, 2, 1, 0};
  }
  return {0, 1, 2, 3};
}

// Which colour (0 r, 1 g, 2 b) sits at each phase of the tile.
inline std::array<int, 4> TileColours(BayerPattern pattern) {
  std::array<int, 4> colours{};
  const std::array<int, 4> channels = TileChannels(pattern);
  for (std::size_t phase = 0; phase < 4; ++phase)
    colours[phase] = channels[phase] == 0 ? 0 : (channels[phase] == 3 ? 2 : 1);
  return colours;
}

inline double Channel(const BayerValues& values, int channel) {
  switch (channel) {
    case 0:
      return values.r;
    case 1:
      return values.gr;
    case 2:
      return values.gb;
    default:
      return values.b;
  }
}

// Black level and 1 / (white - black) of each phase, from the raw format's per-channel levels.
struct PhaseLevels {
  std::array<float, 4> black{};
  std::array<float, 4> scale{};
};

inline PhaseLevels LevelsOf(const RawFormat& format, const std::string& source) {
  const std::array<int, 4> tile = TileChannels(format.mosaic);
  PhaseLevels levels;
  for (int phase = 0; phase < 4; ++phase) {
    const double black = Channel(format.black, tile[static_cast<std::size_t>(phase)]);
    const double white = Channel(format.white, tile[static_cast<std::size_t>(phase)]);
    if (!(white > black))
      throw Error(source + ": white level (" + std::to_string(white) + ") must exceed the black level (" +
                  std::to_string(black) + ")");
    levels.black[static_cast<std::size_t>(phase)] = static_cast<float>(black);
    levels.scale[static_cast<std::size_t>(phase)] = static_cast<float>(1.0 / (white - black));
  }
  return levels;
}

}  // namespace lfsp::decode
