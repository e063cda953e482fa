#pragma once

#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {

// The hexagonal lattice while it is being fitted: lens (i, j) with rows counted from a reference lens at the origin
// (row 0 unshifted, row j shifted right by half a pitch when j is odd). Both grid estimators (white-image centroids
// and capture periodicity) fit this form, then index it as the camera does with GridFromLattice.
struct Lattice {
  double rotation = 0.0;  // rad: lens rows run along (cos, sin)
  double sx = 0.0;        // px along a row
  double sy = 0.0;        // px between rows
  double ox = 0.0;        // px: the reference lens centre
  double oy = 0.0;

  static int Shift(int j) { return ((j % 2) + 2) % 2; }
  void Predict(int i, int j, double& x, double& y) const;
  // Lattice coordinates (a in pitches along the row, b in rows) of a sensor point.
  void Coordinates(double x, double y, double& a, double& b) const;
  void Nearest(double x, double y, int& i, int& j) const;
};

// The lattice indexed as the camera does: the lens nearest the optical axis (axis_x, axis_y) sits in an unshifted
// row; lens (0, 0) is the top-left lens whose micro-image lies wholly on a width x height sensor. Fit statistics are
// left at zero. lfsp::Error if fewer than 2 x 2 lenses fit on the sensor.
LensletGrid GridFromLattice(const Lattice& lattice, double axis_x, double axis_y, int width, int height);

}  // namespace lfsp::decode
