#include "lattice.h"

#include <algorithm>

#include "lfsp/core/error.h"

namespace lfsp::decode {

LensletGrid GridFromLattice(const HexLattice& lattice, double axis_x, double axis_y, int width, int height) {
  int axis_i = 0, axis_j = 0;
  lattice.Nearest(axis_x, axis_y, axis_i, axis_j);
  LensletGrid grid;
  grid.spacing_x = lattice.spacing_x;
  grid.spacing_y = lattice.spacing_y;
  grid.rotation = lattice.rotation;
  // Counted from the axis lens, whose row is taken as unshifted: the same centres, indexed from the axis.
  lattice.Centre(axis_i, axis_j, grid.origin_x, grid.origin_y);
  grid.row_shift = 0;
  grid.sensor_width = width;
  grid.sensor_height = height;
  auto inside = [&](int i, int j) {
    double x = 0.0, y = 0.0;
    grid.Centre(i, j, x, y);
    return grid.MicroImageOnSensor(x, y, width, height);
  };
  const int limit = static_cast<int>(std::max(width, height) / grid.spacing_y) + 4;
  const LensRange range = UsableLensRange(inside, limit, 4);
  grid.Reindex(range.i0, range.j0);
  grid.columns = range.Columns();
  grid.rows = range.Rows();
  if (grid.columns < 2 || grid.rows < 2) throw Error("lenslet grid: fewer than 2x2 usable micro-lenses");
  return grid;
}

}  // namespace lfsp::decode
