#pragma once

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

}  // namespace lfsp::decode
