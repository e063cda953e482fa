#include "lfsp/core/plane_fit.h"

#include <cmath>
#include <opencv2/core.hpp>

namespace lfsp {

void PlaneSums::Add(double x, double y, double d, double weight) {
  const cv::Vec3d p(x, y, 1.0);
  m += (p * weight) * p.t();
  r += p * (weight * d);
  n += 1.0;
}

bool SolvePlane(const cv::Matx33d& m, const cv::Vec3d& r, cv::Vec3d& abc) {
  const double n = m(2, 2);
  if (n <= 0.0) return false;
  const double mx = m(0, 2) / n, my = m(1, 2) / n;
  const cv::Matx33d t(1, 0, -mx, 0, 1, -my, 0, 0, 1);
  const cv::Matx33d centred = t * m * t.t();
  const cv::Vec3d centred_r = t * r;
  const double sxx = centred(0, 0), syy = centred(1, 1), sxy = centred(0, 1);
  if (sxx + syy <= 0.0 || sxx * syy - sxy * sxy < 1e-6 * (sxx + syy) * (sxx + syy)) return false;
  cv::Vec3d p;
  if (!cv::solve(centred, centred_r, p, cv::DECOMP_CHOLESKY)) return false;
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return false;
  abc = {p[0], p[1], p[2] - p[0] * mx - p[1] * my};
  return true;
}

}  // namespace lfsp
