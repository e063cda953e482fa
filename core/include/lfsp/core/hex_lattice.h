#pragma once

#include <functional>

namespace lfsp {

// The geometry of a hexagonal micro-lens lattice on a sensor, in pixels (pixel centres at integer coordinates,
// y down), shared by the decoder's fitted grid and the simulator's camera model:
//   centre(i, j) = origin + R(rotation) * ((i + shift(j) / 2) * spacing_x, j * spacing_y),
//   shift(j) = (j + row_shift) mod 2, R(a) = [cos a, -sin a; sin a, cos a].
// "Along" and "across" are the lattice frame's axes: along a lens row and across the rows.
struct HexLattice {
  double spacing_x = 0.0;  // px between neighbouring centres along a lens row
  double spacing_y = 0.0;  // px between lens rows (about spacing_x * sqrt(3)/2)
  double rotation = 0.0;   // rad: lens rows run along (cos, sin) in image coordinates
  double origin_x = 0.0;   // px: where lens (0, 0) would sit if its row were unshifted
  double origin_y = 0.0;
  int row_shift = 0;  // rows with (j + row_shift) odd are shifted by half a pitch to the right

  int Shift(int j) const { return ((j + row_shift) % 2 + 2) % 2; }
  void Centre(double i, int j, double& x, double& y) const;
  // Sensor position of lattice coordinates (a along the row in lens pitches, b across in rows) plus an offset
  // (along, across) in pixels in the lattice frame.
  void SensorPosition(double a, double b, double along, double across, double& x, double& y) const;
  // The inverse: lattice coordinates (a in pitches, b in rows) of a sensor point.
  void Coordinates(double x, double y, double& a, double& b) const;
  // Lattice-frame offset (along, across) in pixels of a sensor point from lens (i, j)'s centre.
  void LocalOffset(double x, double y, int i, int j, double& along, double& across) const;
  // The lens (i, j) whose centre is nearest to sensor point (x, y); indices are not bounded.
  void Nearest(double x, double y, int& i, int& j) const;

  // Whether a micro-image of radius spacing_x / 2 centred at (x, y) lies wholly on a width x height sensor.
  bool MicroImageOnSensor(double x, double y, int width, int height) const;

  // Re-indexes so that lens (i0, j0) becomes lens (0, 0); every centre stays where it is.
  void Reindex(int i0, int j0);
};

// A rectangle of lens indices, i0 <= i <= i1 and j0 <= j <= j1.
struct LensRange {
  int i0 = 0;
  int i1 = 0;
  int j0 = 0;
  int j1 = 0;
  int Columns() const { return i1 - i0 + 1; }
  int Rows() const { return j1 - j0 + 1; }
};

// The largest rectangle of lenses, grown from lens (0, 0), that are all `usable` (in practice: their micro-image
// is on the sensor): the widest run of columns usable in rows 0 and 1 (rows alternate in shift), then every row
// whose end lenses are usable. A rotated lattice's columns drift sideways from row to row, so the widest columns may
// leave few rows whole: up to `max_trim` columns at either end are given up when that keeps more lenses in all.
// No index goes beyond +-limit.
LensRange UsableLensRange(const std::function<bool(int i, int j)>& usable, int limit, int max_trim);

}  // namespace lfsp
