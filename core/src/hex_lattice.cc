#include "lfsp/core/hex_lattice.h"

#include <cmath>
#include <limits>

namespace lfsp {

void HexLattice::Centre(double i, int j, double& x, double& y) const {
  SensorPosition(i + 0.5 * Shift(j), j, 0.0, 0.0, x, y);
}

void HexLattice::SensorPosition(double a, double b, double along, double across, double& x, double& y) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double p = a * spacing_x + along, q = b * spacing_y + across;
  x = origin_x + c * p - s * q;
  y = origin_y + s * p + c * q;
}

void HexLattice::Coordinates(double x, double y, double& a, double& b) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double dx = x - origin_x, dy = y - origin_y;
  a = (c * dx + s * dy) / spacing_x;
  b = (-s * dx + c * dy) / spacing_y;
}

void HexLattice::LocalOffset(double x, double y, int i, int j, double& along, double& across) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double dx = x - origin_x, dy = y - origin_y;
  along = c * dx + s * dy - (static_cast<double>(i) + 0.5 * Shift(j)) * spacing_x;
  across = -s * dx + c * dy - static_cast<double>(j) * spacing_y;
}

void HexLattice::Nearest(double x, double y, int& i, int& j) const {
  double along = 0.0, across = 0.0;
  Coordinates(x, y, along, across);
  // The nearest centre is in the row below or above the point; in each, the nearest lens is the rounded one.
  const int j0 = static_cast<int>(std::floor(across));
  double best = std::numeric_limits<double>::max();
  for (int jj = j0; jj <= j0 + 1; ++jj) {
    const int ii = static_cast<int>(std::lround(along - 0.5 * Shift(jj)));
    const double ea = (along - ii - 0.5 * Shift(jj)) * spacing_x, eb = (across - jj) * spacing_y;
    if (ea * ea + eb * eb < best) {
      best = ea * ea + eb * eb;
      i = ii;
      j = jj;
    }
  }
}

bool HexLattice::MicroImageOnSensor(double x, double y, int width, int height) const {
  const double edge = 0.5 * spacing_x;
  return x >= edge && y >= edge && x <= width - 1 - edge && y <= height - 1 - edge;
}

void HexLattice::Reindex(int i0, int j0) {
  double x = 0.0, y = 0.0;
  Centre(i0, j0, x, y);
  row_shift = ((row_shift + j0) % 2 + 2) % 2;
  origin_x = x;
  origin_y = y;
  // Centre(0, 0) includes the half-pitch shift when row 0 is shifted: compensate along the row.
  if (Shift(0) == 1) {
    origin_x -= 0.5 * spacing_x * std::cos(rotation);
    origin_y -= 0.5 * spacing_x * std::sin(rotation);
  }
}

LensRange UsableLensRange(const std::function<bool(int i, int j)>& usable, int limit, int max_trim) {
  auto both_rows = [&](int i) { return usable(i, 0) && usable(i, 1); };
  int widest0 = 0, widest1 = 0;
  while (both_rows(widest0 - 1) && widest0 > -limit) --widest0;
  while (both_rows(widest1 + 1) && widest1 < limit) ++widest1;
  LensRange best{widest0, widest1, 0, 0};
  long best_lenses = -1;
  for (int trim_left = 0; trim_left <= max_trim; ++trim_left)
    for (int trim_right = 0; trim_right <= max_trim; ++trim_right) {
      const int a = widest0 + trim_left, b = widest1 - trim_right;
      // A trimmed range keeps at least two columns; the untrimmed one is taken whatever it is.
      if ((trim_left > 0 || trim_right > 0) && b - a < 1) continue;
      auto row_usable = [&](int j) { return usable(a, j) && usable(b, j); };
      int top = 0, bottom = 0;
      while (row_usable(top - 1) && top > -limit) --top;
      while (row_usable(bottom + 1) && bottom < limit) ++bottom;
      const long lenses = static_cast<long>(b - a + 1) * (bottom - top + 1);
      if (lenses > best_lenses) {
        best_lenses = lenses;
        best = {a, b, top, bottom};
      }
    }
  return best;
}

}  // namespace lfsp
