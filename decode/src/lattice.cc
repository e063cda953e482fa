#include "lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lfsp/core/error.h"

namespace lfsp::decode {

void Lattice::Predict(int i, int j, double& x, double& y) const {
  const double a = (i + 0.5 * Shift(j)) * sx, b = j * sy;
  const double c = std::cos(rotation), s = std::sin(rotation);
  x = ox + c * a - s * b;
  y = oy + s * a + c * b;
}

void Lattice::Coordinates(double x, double y, double& a, double& b) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double dx = x - ox, dy = y - oy;
  a = (c * dx + s * dy) / sx;
  b = (-s * dx + c * dy) / sy;
}

void Lattice::Nearest(double x, double y, int& i, int& j) const {
  double a = 0.0, b = 0.0;
  Coordinates(x, y, a, b);
  double best = std::numeric_limits<double>::max();
  const int j0 = static_cast<int>(std::floor(b));
  for (int jj = j0; jj <= j0 + 1; ++jj) {
    const int ii = static_cast<int>(std::lround(a - 0.5 * Shift(jj)));
    double px = 0.0, py = 0.0;
    Predict(ii, jj, px, py);
    const double d = (px - x) * (px - x) + (py - y) * (py - y);
    if (d < best) {
      best = d;
      i = ii;
      j = jj;
    }
  }
}

LensletGrid GridFromLattice(const Lattice& lattice, double axis_x, double axis_y, int width, int height) {
  int axis_i = 0, axis_j = 0;
  lattice.Nearest(axis_x, axis_y, axis_i, axis_j);
  LensletGrid grid;
  grid.spacing_x = lattice.sx;
  grid.spacing_y = lattice.sy;
  grid.rotation = lattice.rotation;
  lattice.Predict(axis_i, axis_j, grid.origin_x, grid.origin_y);
  grid.row_shift = 0;
  grid.sensor_width = width;
  grid.sensor_height = height;
  const double edge = 0.5 * grid.spacing_x;
  auto inside = [&](int i, int j) {
    double x = 0.0, y = 0.0;
    grid.Centre(i, j, x, y);
    return x >= edge && y >= edge && x <= width - 1 - edge && y <= height - 1 - edge;
  };
  const int limit = static_cast<int>(std::max(width, height) / grid.spacing_y) + 4;
  // The widest run of columns in the axis row and the next (rows alternate in shift).
  auto both_rows = [&](int i) { return inside(i, 0) && inside(i, 1); };
  int widest0 = 0, widest1 = 0;
  while (both_rows(widest0 - 1) && widest0 > -limit) --widest0;
  while (both_rows(widest1 + 1) && widest1 < limit) ++widest1;
  // A rotated lattice's columns drift sideways from row to row, so the widest rows may leave few rows whole: give
  // up a few columns at either end when that keeps more lenses in all.
  int i0 = widest0, i1 = widest1, j0 = 0, j1 = 0;
  long best_lenses = -1;
  for (int trim_left = 0; trim_left <= 4; ++trim_left)
    for (int trim_right = 0; trim_right <= 4; ++trim_right) {
      const int a = widest0 + trim_left, b = widest1 - trim_right;
      if (b - a < 1) continue;
      auto row_inside = [&](int j) { return inside(a, j) && inside(b, j); };
      int top = 0, bottom = 0;
      while (row_inside(top - 1) && top > -limit) --top;
      while (row_inside(bottom + 1) && bottom < limit) ++bottom;
      const long lenses = static_cast<long>(b - a + 1) * (bottom - top + 1);
      if (lenses > best_lenses) {
        best_lenses = lenses;
        i0 = a;
        i1 = b;
        j0 = top;
        j1 = bottom;
      }
    }
  double first_x = 0.0, first_y = 0.0;
  grid.Centre(i0, j0, first_x, first_y);
  grid.row_shift = ((j0 % 2) + 2) % 2;
  grid.origin_x = first_x;
  grid.origin_y = first_y;
  if (grid.Shift(0) == 1) {
    grid.origin_x -= 0.5 * grid.spacing_x * std::cos(grid.rotation);
    grid.origin_y -= 0.5 * grid.spacing_x * std::sin(grid.rotation);
  }
  grid.columns = i1 - i0 + 1;
  grid.rows = j1 - j0 + 1;
  if (grid.columns < 2 || grid.rows < 2) throw Error("lenslet grid: fewer than 2x2 usable micro-lenses");
  return grid;
}

}  // namespace lfsp::decode
