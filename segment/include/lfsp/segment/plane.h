#pragma once

namespace lfsp::segment {

// A slanted disparity plane of one superpixel, in centre-view pixel coordinates (docs/DESIGN.md disparity convention):
// d(x0, y0) = a x0 + b y0 + c.
struct Plane {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;

  double AtCentre(double x0, double y0) const { return a * x0 + b * y0 + c; }

  // Disparity of the ray through pixel (x, y) of the view at offset (du, dv) = (u - uc, v - vc) from the centre
  // (Eq. 2 with the project's sign: that ray meets the centre view at x0 = x + du d, y0 = y + dv d).
  double AtRay(double x, double y, double du, double dv) const {
    const double denominator = 1.0 - a * du - b * dv;
    return (a * x + b * y + c) / denominator;
  }
};

}  // namespace lfsp::segment
