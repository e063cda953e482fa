#include "lfsp/calibrate/ray_model.h"

#include <Eigen/LU>

namespace lfsp::calibrate {

Ray RayModel::MeasuredRay(double i, double j, double k, double l) const {
  const Vector5d phi = H * Vector5d(i, j, k, l, 1.0);
  return {phi(0), phi(1), phi(2), phi(3)};
}

Ray RayModel::PhysicalRay(double i, double j, double k, double l) const {
  Ray ray = MeasuredRay(i, j, k, l);
  const auto d = distortion.ToArray();
  DistortDirection(d.data(), ray.u, ray.v, ray.u, ray.v);
  return ray;
}

void UndistortDirection(const Distortion& distortion, double u, double v, int iterations, double& u_out,
                        double& v_out) {
  // Solve (1 + k(r)) (m - b) + b = p for m: m = b + (p - b) / (1 + k(|m - b|)), starting from m = p. The radial
  // factor changes slowly with m, so each iteration gains about a factor k1 r^2 in accuracy.
  const double pu = u - distortion.b1, pv = v - distortion.b2;
  double mu = pu, mv = pv;
  for (int n = 0; n < iterations; ++n) {
    const double r2 = mu * mu + mv * mv;
    const double radial = 1.0 + r2 * (distortion.k1 + r2 * (distortion.k2 + r2 * distortion.k3));
    mu = pu / radial;
    mv = pv / radial;
  }
  u_out = mu + distortion.b1;
  v_out = mv + distortion.b2;
}

Eigen::Vector4d RayModel::IndexOf(const Ray& ray, int iterations) const {
  double u = ray.u, v = ray.v;
  if (iterations > 0) UndistortDirection(distortion, ray.u, ray.v, iterations, u, v);
  const Vector5d n = H.partialPivLu().solve(Vector5d(ray.s, ray.t, u, v, 1.0));
  return n.head<4>() / n(4);
}

Slopes RayModel::GetSlopes() const { return {H(0, 0), H(0, 2), H(2, 0), H(2, 2), H(1, 1), H(1, 3), H(3, 1), H(3, 3)}; }

Eigen::Vector4d CentreIndex(const LightFieldShape& shape) {
  return {(shape.width - 1) / 2.0, (shape.height - 1) / 2.0, (shape.nu - 1) / 2.0, (shape.nv - 1) / 2.0};
}

void RecentreIntrinsics(Matrix5d& H, const LightFieldShape& shape) {
  const Eigen::Vector4d centre = CentreIndex(shape);
  for (int r = 0; r < 4; ++r) H(r, 4) = -H.block<1, 4>(r, 0).dot(centre);
}

Matrix5d IntrinsicsFromSlopes(const Slopes& slopes, const LightFieldShape& shape) {
  Matrix5d H = Matrix5d::Zero();
  H(0, 0) = slopes[0];
  H(0, 2) = slopes[1];
  H(2, 0) = slopes[2];
  H(2, 2) = slopes[3];
  H(1, 1) = slopes[4];
  H(1, 3) = slopes[5];
  H(3, 1) = slopes[6];
  H(3, 3) = slopes[7];
  H(4, 4) = 1.0;
  RecentreIntrinsics(H, shape);
  return H;
}

}  // namespace lfsp::calibrate
