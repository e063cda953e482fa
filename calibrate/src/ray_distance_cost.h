#pragma once

// The residual of one observed checker corner (calibration.h): the 3-D distance between the corner and the
// physical ray of the sample index where it was seen, as a 3-vector (the component of the corner's offset from the
// ray origin that is perpendicular to the ray), in millimetres so the solver's tolerances see numbers near 1.

#include <ceres/autodiff_cost_function.h>
#include <ceres/rotation.h>

#include "lfsp/calibrate/ray_model.h"

namespace lfsp::calibrate::internal {

// One observation: centred sample index (i, j, k, l minus the centre sample) and the board point (x, y, 0) in m.
struct Observation {
  int capture = 0;
  double i = 0, j = 0, k = 0, l = 0;
  double x = 0, y = 0;
};

struct RayDistanceCost {
  explicit RayDistanceCost(const Observation& o) : obs(o) {}

  // slopes: H11 H13 H31 H33 H22 H24 H42 H44; distortion: k1 k2 k3 b1 b2; pose: angle-axis (3), translation (3).
  template <typename T>
  bool operator()(const T* slopes, const T* distortion, const T* pose, T* residual) const {
    // Offsets vanish for centred indices (recentring).
    const T s = slopes[0] * obs.i + slopes[1] * obs.k;
    const T u_measured = slopes[2] * obs.i + slopes[3] * obs.k;
    const T t = slopes[4] * obs.j + slopes[5] * obs.l;
    const T v_measured = slopes[6] * obs.j + slopes[7] * obs.l;
    T u, v;
    DistortDirection(distortion, u_measured, v_measured, u, v);
    const T board[3] = {T(obs.x), T(obs.y), T(0.0)};
    T p[3];
    ceres::AngleAxisRotatePoint(pose, board, p);
    const T w0 = p[0] + pose[3] - s;
    const T w1 = p[1] + pose[4] - t;
    const T w2 = p[2] + pose[5];
    // |w x d| / |d| is the distance from the corner to the ray with direction d = (u, v, 1).
    const T scale = T(1000.0) / ceres::sqrt(u * u + v * v + T(1.0));
    residual[0] = (w1 - w2 * v) * scale;
    residual[1] = (w2 * u - w0) * scale;
    residual[2] = (w0 * v - w1 * u) * scale;
    return true;
  }

  static ceres::CostFunction* Create(const Observation& o) {
    return new ceres::AutoDiffCostFunction<RayDistanceCost, 3, 8, 5, 6>(new RayDistanceCost(o));
  }

  Observation obs;
};

}  // namespace lfsp::calibrate::internal
