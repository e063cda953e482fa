#pragma once

// The lenslet-camera ray model of Dansereau, Pizarro and Williams (CVPR 2013, "DPW").
//
// A sample index n = (i, j, k, l, 1) of a decoded light field, with i, j the pixel column and row inside a view and
// k, l the view column and row (x, y, u, v in docs/DESIGN.md; all 0-based), maps to a ray phi = (s, t, u, v, 1) = H n
// in a relative two-plane parameterisation with plane separation 1 m: the ray leaves (s, t, 0) in the camera frame (x
// right, y down, z forward, metres) with direction (u, v, 1).
//
// H has eight slopes: s = H11 i + H13 k, t = H22 j + H24 l, u = H31 i + H33 k, v = H42 j + H44 l, plus offsets
// H15, H25, H35, H45 that are fixed by recentring: the centre sample ((W-1)/2, (H-1)/2, (nu-1)/2, (nv-1)/2) maps
// to the ray (0, 0, 0, 0) (the offsets are redundant with the pose of the camera, as in LFToolbox).
//
// Radial distortion with decentring acts on the direction only (LFToolbox order k1, k2, k3, b1, b2):
//   physical (u, v) = (1 + k1 r^2 + k2 r^4 + k3 r^6) ((u, v) - b) + b,   r = |(u, v) - b|,
// where (u, v) comes from H n. It maps the ray a sample measures to the ray the scene sends.

#include <Eigen/Core>
#include <array>

#include "lfsp/core/light_field.h"

namespace lfsp::calibrate {

using Matrix5d = Eigen::Matrix<double, 5, 5>;
using Vector5d = Eigen::Matrix<double, 5, 1>;

struct Distortion {
  double k1 = 0, k2 = 0, k3 = 0;  // radial terms in r^2, r^4, r^6
  double b1 = 0, b2 = 0;          // decentring (ray-direction units)

  std::array<double, 5> ToArray() const { return {k1, k2, k3, b1, b2}; }
  static Distortion FromArray(const std::array<double, 5>& a) { return {a[0], a[1], a[2], a[3], a[4]}; }
  bool IsZero() const { return k1 == 0 && k2 == 0 && k3 == 0; }
};

// Physical direction from a measured one (the forward model above). Templated so Ceres can differentiate it.
// `d` holds k1, k2, k3, b1, b2.
template <typename T>
void DistortDirection(const T* d, const T& u, const T& v, T& u_out, T& v_out) {
  const T du = u - d[3];
  const T dv = v - d[4];
  const T r2 = du * du + dv * dv;
  const T radial = T(1.0) + r2 * (d[0] + r2 * (d[1] + r2 * d[2]));
  u_out = radial * du + d[3];
  v_out = radial * dv + d[4];
}

// The eight free slopes in the order the solver keeps them: H11, H13, H31, H33 (horizontal: s, u from i, k) and
// H22, H24, H42, H44 (vertical: t, v from j, l).
using Slopes = std::array<double, 8>;

// A ray in the camera frame: origin (s, t, 0), direction (u, v, 1).
struct Ray {
  double s = 0, t = 0, u = 0, v = 0;
};

struct RayModel {
  Matrix5d H = Matrix5d::Identity();
  Distortion distortion;

  // The ray H n without distortion (what the index measures) and the physical ray (after distortion).
  Ray MeasuredRay(double i, double j, double k, double l) const;
  Ray PhysicalRay(double i, double j, double k, double l) const;

  // The sample index (i, j, k, l) whose physical ray is `ray`: inverse distortion by fixed-point iteration, then
  // H^-1. `iterations` = 0 skips the distortion.
  Eigen::Vector4d IndexOf(const Ray& ray, int iterations = 8) const;

  Slopes GetSlopes() const;
};

// The measured direction whose distortion gives the physical one (fixed-point iteration, as LFToolbox does).
void UndistortDirection(const Distortion& distortion, double u, double v, int iterations, double& u_out, double& v_out);

// H from the eight slopes, recentred for a light field of this shape.
Matrix5d IntrinsicsFromSlopes(const Slopes& slopes, const LightFieldShape& shape);

// Sets the offsets H(0:3, 4) so that the centre sample of `shape` maps to the ray (0, 0, 0, 0).
void RecentreIntrinsics(Matrix5d& H, const LightFieldShape& shape);

// The centre sample index ((W-1)/2, (H-1)/2, (nu-1)/2, (nv-1)/2).
Eigen::Vector4d CentreIndex(const LightFieldShape& shape);

}  // namespace lfsp::calibrate
