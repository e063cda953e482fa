#include "lfsp/calibrate/rectify.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "lfsp/core/error.h"

namespace lfsp::calibrate {
namespace {

// Linear interpolation weights of a coordinate inside [0, size - 1]. View coordinates may stray up to half a view
// outside the grid (the edge views' rays move slightly when the distortion is removed): they use the edge view.
struct Tap {
  int lo = 0;
  int hi = 0;
  double frac = 0;
};

bool MakeTap(double coordinate, int size, double clamp_margin, Tap& tap) {
  // NaN passes every comparison below and would become an index: a ray that does not map anywhere is outside.
  if (!std::isfinite(coordinate)) return false;
  if (coordinate < -clamp_margin || coordinate > size - 1 + clamp_margin) return false;
  coordinate = std::clamp(coordinate, 0.0, static_cast<double>(size - 1));
  tap.lo = std::min(static_cast<int>(std::floor(coordinate)), size - 1);
  tap.hi = std::min(tap.lo + 1, size - 1);
  tap.frac = coordinate - tap.lo;
  return true;
}

}  // namespace

RayModel RectifiedModel(const RayModel& calibrated, const LightFieldShape& shape) {
  const Slopes s = calibrated.GetSlopes();
  const double position = 0.5 * (s[0] + s[4]);     // H11, H22
  const double baseline = 0.5 * (s[1] + s[5]);     // H13, H24
  const double pixel = 0.5 * (s[2] + s[6]);        // H31, H42
  const double convergence = 0.5 * (s[3] + s[7]);  // H33, H44
  RayModel rectified;
  rectified.H =
      IntrinsicsFromSlopes({position, baseline, pixel, convergence, position, baseline, pixel, convergence}, shape);
  return rectified;
}

LightField Rectify(const LightField& input, const RayModel& calibrated, const RayModel& rectified,
                   const RectifyOptions& options) {
  if (input.empty()) throw Error("rectify: the light field is empty");
  if (input.shape().channels > 4) throw Error("rectify: at most 4 channels are supported");
  const LightFieldShape& shape = input.shape();
  LightField output(shape);
  output.transfer = input.transfer;
  output.metadata = input.metadata;
  output.EnableWeights(0.0f);
  const Matrix5d to_measured = calibrated.H.inverse();
  if (!to_measured.allFinite() || !rectified.H.allFinite())
    throw Error("rectify: the calibration matrix H cannot be inverted in floating point");
  const int channels = shape.channels;
  const int rows = shape.nv * shape.nu * shape.height;

#pragma omp parallel for schedule(static)
  for (int row = 0; row < rows; ++row) {
    const int y = row % shape.height;
    const int cam = row / shape.height;
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    float* out = output.ViewData(view) + static_cast<std::size_t>(y) * shape.width * channels;
    float* out_weight = output.weights().ViewData(view) + static_cast<std::size_t>(y) * shape.width;
    for (int x = 0; x < shape.width; ++x) {
      // Ideal ray of this output sample, then the measured index that recorded it.
      Ray ray = rectified.PhysicalRay(x, y, view.u, view.v);
      UndistortDirection(calibrated.distortion, ray.u, ray.v, options.inverse_distortion_iterations, ray.u, ray.v);
      const Vector5d n = to_measured * Vector5d(ray.s, ray.t, ray.u, ray.v, 1.0);
      Tap ti, tj, tk, tl;
      if (!MakeTap(n(0), shape.width, 1e-6, ti) || !MakeTap(n(1), shape.height, 1e-6, tj) ||
          !MakeTap(n(2), shape.nu, 0.5, tk) || !MakeTap(n(3), shape.nv, 0.5, tl)) {
        for (int c = 0; c < channels; ++c) out[x * channels + c] = 0.0f;
        out_weight[x] = 0.0f;
        continue;
      }
      double value[4] = {0, 0, 0, 0};
      double weight = 0;
      for (int corner = 0; corner < 16; ++corner) {
        const int i = (corner & 1) ? ti.hi : ti.lo, j = (corner & 2) ? tj.hi : tj.lo;
        const int k = (corner & 4) ? tk.hi : tk.lo, l = (corner & 8) ? tl.hi : tl.lo;
        const double w = ((corner & 1) ? ti.frac : 1 - ti.frac) * ((corner & 2) ? tj.frac : 1 - tj.frac) *
                         ((corner & 4) ? tk.frac : 1 - tk.frac) * ((corner & 8) ? tl.frac : 1 - tl.frac);
        if (w == 0) continue;
        const ViewIndex source{k, l};
        for (int c = 0; c < channels && c < 4; ++c) value[c] += w * input.at(source, j, i, c);
        weight += w * (input.HasWeights() ? input.weights().at(source, j, i, 0) : 1.0);
      }
      for (int c = 0; c < channels; ++c)
        out[x * channels + c] = static_cast<float>(std::clamp(value[std::min(c, 3)], 0.0, 1.0));
      out_weight[x] = static_cast<float>(weight);
    }
  }
  return output;
}

}  // namespace lfsp::calibrate
