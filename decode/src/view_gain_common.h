#pragma once

// What the two per-view gain flattenings (lattice_gain.cc: the Bayer tile under each lens; jpeg_block_gain.cc: the
// JPEG's blocks) share: where each decoded pixel's nearest lens sits on the sensor, and the loop over the lit views
// that makes their per-view figures one report.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "lfsp/core/hex_lattice.h"
#include "lfsp/core/light_field.h"

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

// What one view's flattening divided out: the rms and the largest deviation of its gain from 1.
struct ViewGainDeviation {
  double rms = 0.0;
  double largest = 0.0;
};

// Runs `flatten(view, weight)` on every view whose mean ray weight reaches `min_mean_weight`, views in parallel
// (`weight`: the view's weights as a CV_32F cv::Mat). It flattens that view in place and returns what it divided
// out, or nothing when it measured no gain. Fills `report`: rms, the mean over the flattened views; max, the largest
// deviation of any; views, how many.
template <class Report, class Flatten>
void FlattenEachLitView(LightField& light_field, double min_mean_weight, Flatten flatten, Report& report) {
  const LightFieldShape& shape = light_field.shape();
  const int views = shape.nu * shape.nv;
  std::vector<std::optional<ViewGainDeviation>> deviations(static_cast<std::size_t>(views));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < views; ++k) {
    const ViewIndex view{k % shape.nu, k / shape.nu};
    const cv::Mat weight(shape.height, shape.width, CV_32F, light_field.weights().ViewData(view));
    if (cv::mean(weight)[0] < min_mean_weight) continue;
    deviations[static_cast<std::size_t>(k)] = flatten(view, weight);
  }
  for (const std::optional<ViewGainDeviation>& deviation : deviations) {
    if (!deviation) continue;
    report.rms += deviation->rms;
    report.max = std::max(report.max, deviation->largest);
    ++report.views;
  }
  if (report.views > 0) report.rms /= report.views;
}

}  // namespace lfsp::decode
