#pragma once

#include <cmath>
#include <limits>

#include "lfsp/core/hex_lattice.h"
#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {

// Both grid estimators (white-image centroids and capture periodicity) fit a HexLattice with rows counted from a
// reference lens at the origin (row_shift 0: row 0 unshifted, row j shifted right by half a pitch when j is odd),
// then index it as the camera does with GridFromLattice.

// The lattice indexed as the camera does: the lens nearest the optical axis (axis_x, axis_y) sits in an unshifted
// row; lens (0, 0) is the top-left lens whose micro-image lies wholly on a width x height sensor. Fit statistics are
// left at zero. lfsp::Error if fewer than 2 x 2 lenses fit on the sensor.
LensletGrid GridFromLattice(const HexLattice& lattice, double axis_x, double axis_y, int width, int height);

// The lens nearest a sensor point given in lattice coordinates (along = the point's coordinate along the lens rows in
// pitches, across = across them in row spacings, HexLattice::Coordinates), and the point's offset from its centre in
// pixels along and across the rows. The nearest centre lies in the row below or above; in each, the nearest lens is
// the rounded one (nearbyint). For per-pixel loops that step the coordinates along a row (LensLabels, the white image
// synthesised from a capture): inlined, so their AVX2 builds make floor and nearbyint instructions.
struct NearestLens {
  int i = 0;
  int j = 0;
  double offset_along = 0.0;
  double offset_across = 0.0;
};

[[gnu::always_inline]] inline NearestLens NearestLensAt(const HexLattice& lattice, double along, double across) {
  const int j0 = static_cast<int>(std::floor(across));
  NearestLens nearest{0, j0};
  double best = std::numeric_limits<double>::max();
  for (int j = j0; j <= j0 + 1; ++j) {
    const double shift = 0.5 * lattice.Shift(j);
    const double i = std::nearbyint(along - shift);
    const double ea = (along - i - shift) * lattice.spacing_x, eb = (across - j) * lattice.spacing_y;
    if (ea * ea + eb * eb < best) {
      best = ea * ea + eb * eb;
      nearest = {static_cast<int>(i), j, ea, eb};
    }
  }
  return nearest;
}

}  // namespace lfsp::decode
