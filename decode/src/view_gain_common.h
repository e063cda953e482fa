#pragma once

// What the two per-view gain flattenings (lattice_gain.cc: the Bayer tile under each lens; jpeg_block_gain.cc: the
// JPEG's blocks) share: where each decoded pixel's nearest lens sits on the sensor, and how their per-view figures
// become one report.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "lfsp/core/hex_lattice.h"

namespace lfsp::decode {

// Calls `visit(x, y, sensor_x, sensor_y)` for every decoded pixel of a view `width` x `height` with the sensor
// position of the lens nearest to where it is sampled, at the lens centre (the slicing's Catmull-Rom mixes up to four
// lenses of the row; the nearest weighs most). DecodedGeometry: x steps by sqrt(3)/2 lens pitches along the row.
template <class Visit>
void ForEachNearestLens(const HexLattice& lattice, int width, int height, Visit visit) {
  const double pitches_per_column = 0.5 * std::numbers::sqrt3;
  for (int y = 0; y < height; ++y) {
    const double shift = 0.5 * lattice.Shift(y);
    for (int x = 0; x < width; ++x) {
      double sx = 0.0, sy = 0.0;
      lattice.SensorPosition(std::nearbyint(x * pitches_per_column - shift) + shift, y, 0.0, 0.0, sx, sy);
      visit(x, y, sx, sy);
    }
  }
}

// Fills `report` (rms, max, views) from each view's rms gain deviation (negative: the view was not measured) and
// largest deviation: the mean rms over the measured views, the largest deviation of any.
template <class Report>
void SummariseViews(const std::vector<double>& rms, const std::vector<double>& largest, Report& report) {
  for (std::size_t k = 0; k < rms.size(); ++k) {
    if (rms[k] < 0.0) continue;
    report.rms += rms[k];
    report.max = std::max(report.max, largest[k]);
    ++report.views;
  }
  if (report.views > 0) report.rms /= report.views;
}

}  // namespace lfsp::decode
