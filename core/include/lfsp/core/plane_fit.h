#pragma once

#include <opencv2/core/matx.hpp>

namespace lfsp {

// Sums for the least-squares fit of a plane d = a x + b y + c to samples (x, y, d), each with a weight w:
// m = sum w (x y 1)^T (x y 1), r = sum w d (x y 1)^T, n = how many samples were added. Depth's slanted-plane
// refinement and segmentation's superpixel planes both fit through these (one formulation, one solver).
struct PlaneSums {
  cv::Matx33d m = cv::Matx33d::zeros();
  cv::Vec3d r = cv::Vec3d::all(0.0);
  double n = 0.0;

  // A point without a disparity: only its geometry, for terms that compare planes over a point set.
  // Inline and written out: m += p p^T and r += p d with p = (x, y, 1), bit for bit the sums of the matrix
  // expression this replaced as long as the compiler does not fuse a multiply and an add (baseline x86-64 has no
  // FMA; with -march=native it may, and the last bits move). LFSP's plane smoothing adds every centre pixel ten
  // times an iteration, and the matrix expression's temporaries were most of that time.
  void Add(double x, double y) {
    m(0, 0) += x * x;
    m(0, 1) += x * y;
    m(0, 2) += x;
    m(1, 0) += y * x;
    m(1, 1) += y * y;
    m(1, 2) += y;
    m(2, 0) += x;
    m(2, 1) += y;
    m(2, 2) += 1.0;
    n += 1.0;
  }
  void Add(double x, double y, double d) {
    Add(x, y);
    r(0) += x * d;
    r(1) += y * d;
    r(2) += d;
  }
  void Add(double x, double y, double d, double weight);
};

// Solves m (a, b, c)^T = r in coordinates centred on the support's (weighted) mean, since absolute pixel
// coordinates make the system badly conditioned. False, leaving `abc` unchanged, if the support is (near)
// degenerate, e.g. collinear, which leaves a slope undetermined, or if the solution is not finite.
bool SolvePlane(const cv::Matx33d& m, const cv::Vec3d& r, cv::Vec3d& abc);

}  // namespace lfsp
