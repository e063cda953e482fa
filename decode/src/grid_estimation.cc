// Lenslet grid estimation from a white image: sub-pixel micro-image centres, then a robust least-squares fit of
// the hexagonal lattice, grown outwards from the optical axis so the metadata's guess only has to be right locally.

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lattice.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

struct Measurement {
  int i = 0;
  int j = 0;
  double x = 0.0;
  double y = 0.0;
  double brightness = 0.0;
  bool valid = false;
  bool inlier = false;
};

// Sub-pixel centre of the micro-image around (cx, cy): the point c where the windowed first moment
//   G(c) = sum_p w(|p - c| / R) I(p) (p - c)
// vanishes, with the smooth window w(t) = 1 - t^2. A micro-image is point-symmetric about its centre, so G is zero
// there whatever the profile (peaked or flat-topped); Newton's method with the analytic Jacobian finds it in a few
// steps, where a plain re-centred centroid would crawl on flat-topped micro-images.
bool RefineCentre(const cv::Mat& grey, double radius, int iterations, double max_shift, double& cx, double& cy,
                  double& brightness) {
  const double r2max = radius * radius;
  const double start_x = cx, start_y = cy;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    const int x0 = static_cast<int>(std::ceil(cx - radius)), x1 = static_cast<int>(std::floor(cx + radius));
    const int y0 = static_cast<int>(std::ceil(cy - radius)), y1 = static_cast<int>(std::floor(cy + radius));
    if (x0 < 0 || y0 < 0 || x1 >= grey.cols || y1 >= grey.rows) return false;
    double gx = 0.0, gy = 0.0, jxx = 0.0, jxy = 0.0, jyy = 0.0, sum_wi = 0.0, sum_w = 0.0;
    for (int y = y0; y <= y1; ++y) {
      const float* row = grey.ptr<float>(y);
      const double dy = y - cy;
      for (int x = x0; x <= x1; ++x) {
        const double dx = x - cx;
        const double r2 = dx * dx + dy * dy;
        if (r2 >= r2max) continue;
        const double w = 1.0 - r2 / r2max;
        const double value = row[x];
        const double wi = w * value;
        gx += wi * dx;
        gy += wi * dy;
        sum_wi += wi;
        sum_w += w;
        // d(w d)/dc = -w I + (2 / R^2) d d^T
        const double k = 2.0 * value / r2max;
        jxx += k * dx * dx;
        jxy += k * dx * dy;
        jyy += k * dy * dy;
      }
    }
    if (!(sum_wi > 0.0)) return false;
    brightness = sum_wi / sum_w;
    jxx -= sum_wi;
    jyy -= sum_wi;
    // Newton step c -= J^-1 G; J is negative definite around a bright micro-image. Fall back to the centroid step
    // otherwise.
    const double det = jxx * jyy - jxy * jxy;
    double step_x = gx / sum_wi, step_y = gy / sum_wi;
    if (jxx < 0.0 && det > 1e-12 * sum_wi * sum_wi) {
      step_x = -(jyy * gx - jxy * gy) / det;
      step_y = -(-jxy * gx + jxx * gy) / det;
    }
    const double step = std::hypot(step_x, step_y);
    const double limit = 0.25 * radius;
    if (step > limit) {
      step_x *= limit / step;
      step_y *= limit / step;
    }
    cx += step_x;
    cy += step_y;
    if (std::hypot(cx - start_x, cy - start_y) > max_shift) return false;
    if (step < 1e-4) break;
  }
  return true;
}

// Gauss-Newton on (rotation, spacing_x, spacing_y, origin_x, origin_y) over the inlier measurements.
void FitLattice(const std::vector<Measurement>& measurements, HexLattice& lattice) {
  for (int iteration = 0; iteration < 6; ++iteration) {
    Eigen::Matrix<double, 5, 5> normal = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> rhs = Eigen::Matrix<double, 5, 1>::Zero();
    const double c = std::cos(lattice.rotation), s = std::sin(lattice.rotation);
    for (const Measurement& m : measurements) {
      if (!m.inlier) continue;
      const double a = m.i + 0.5 * lattice.Shift(m.j), b = m.j;
      double px = 0.0, py = 0.0;
      lattice.Centre(m.i, m.j, px, py);
      Eigen::Matrix<double, 5, 1> jx, jy;
      jx << -s * lattice.spacing_x * a - c * lattice.spacing_y * b, c * a, -s * b, 1.0, 0.0;
      jy << c * lattice.spacing_x * a - s * lattice.spacing_y * b, s * a, c * b, 0.0, 1.0;
      normal += jx * jx.transpose() + jy * jy.transpose();
      rhs += jx * (m.x - px) + jy * (m.y - py);
    }
    const Eigen::Matrix<double, 5, 1> delta = normal.ldlt().solve(rhs);
    if (!delta.allFinite()) throw Error("lenslet grid: the fit is singular (too few micro-images found)");
    lattice.rotation += delta(0);
    lattice.spacing_x += delta(1);
    lattice.spacing_y += delta(2);
    lattice.origin_x += delta(3);
    lattice.origin_y += delta(4);
    if (std::abs(delta(0)) < 1e-12 && delta.tail<4>().cwiseAbs().maxCoeff() < 1e-9) break;
  }
}

double Residual(const HexLattice& lattice, const Measurement& m) {
  double px = 0.0, py = 0.0;
  lattice.Centre(m.i, m.j, px, py);
  return std::hypot(m.x - px, m.y - py);
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Measures every micro-image within `reach` lenses of the first one (all if reach < 0) at the lattice's predicted
// positions, then fits the lattice robustly: dim micro-images are dropped, then centroids far from a first fit.
std::vector<Measurement> MeasureAndFit(const cv::Mat& grey, const GridEstimateOptions& options, int reach,
                                       HexLattice& lattice) {
  const double radius = options.window_radius * lattice.spacing_x;
  // Index bounds of lenses whose predicted centre is on the sensor.
  double a_min = std::numeric_limits<double>::max(), a_max = -a_min, b_min = a_min, b_max = -a_min;
  for (const auto& [x, y] :
       {std::pair{0.0, 0.0}, {grey.cols - 1.0, 0.0}, {0.0, grey.rows - 1.0}, {grey.cols - 1.0, grey.rows - 1.0}}) {
    double a = 0.0, b = 0.0;
    lattice.Coordinates(x, y, a, b);
    a_min = std::min(a_min, a);
    a_max = std::max(a_max, a);
    b_min = std::min(b_min, b);
    b_max = std::max(b_max, b);
  }
  int i0 = static_cast<int>(std::floor(a_min)) - 1, i1 = static_cast<int>(std::ceil(a_max)) + 1;
  int j0 = static_cast<int>(std::floor(b_min)) - 1, j1 = static_cast<int>(std::ceil(b_max)) + 1;
  if (reach >= 0) {
    i0 = std::max(i0, -reach);
    i1 = std::min(i1, reach);
    j0 = std::max(j0, -reach);
    j1 = std::min(j1, reach);
  }
  const int columns = i1 - i0 + 1;
  std::vector<Measurement> measurements(static_cast<std::size_t>(columns) * static_cast<std::size_t>(j1 - j0 + 1));
#pragma omp parallel for schedule(dynamic, 4)
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      Measurement& m = measurements[static_cast<std::size_t>(j - j0) * columns + static_cast<std::size_t>(i - i0)];
      m.i = i;
      m.j = j;
      lattice.Centre(i, j, m.x, m.y);
      m.valid =
          RefineCentre(grey, radius, options.centroid_iterations, 0.35 * lattice.spacing_x, m.x, m.y, m.brightness);
    }
  }
  std::erase_if(measurements, [](const Measurement& m) { return !m.valid; });
  if (measurements.size() < 7) throw Error("lenslet grid: fewer than 7 micro-images found near the optical axis");
  std::vector<double> brightness;
  brightness.reserve(measurements.size());
  for (const Measurement& m : measurements) brightness.push_back(m.brightness);
  const double bright_enough = options.min_brightness * Median(brightness);
  for (Measurement& m : measurements) m.inlier = m.brightness >= bright_enough;
  for (int round = 0; round < 3; ++round) {
    FitLattice(measurements, lattice);
    std::vector<double> residuals;
    for (const Measurement& m : measurements)
      if (m.brightness >= bright_enough) residuals.push_back(Residual(lattice, m));
    const double sigma = 1.4826 * Median(residuals);
    const double limit = std::max(options.outlier_sigmas * sigma, options.min_outlier_px);
    for (Measurement& m : measurements) m.inlier = m.brightness >= bright_enough && Residual(lattice, m) <= limit;
  }
  return measurements;
}

// The brightest point near (x, y), on a lightly smoothed copy of a small patch.
void BrightestNear(const cv::Mat& grey, double x, double y, double reach, double& bx, double& by) {
  const int r = static_cast<int>(std::ceil(reach));
  const cv::Rect patch =
      cv::Rect(static_cast<int>(std::lround(x)) - r, static_cast<int>(std::lround(y)) - r, 2 * r + 1, 2 * r + 1) &
      cv::Rect(0, 0, grey.cols, grey.rows);
  if (patch.width < 3 || patch.height < 3) throw Error("lenslet grid: the optical axis guess is off the sensor");
  cv::Mat smooth;
  cv::blur(grey(patch), smooth, cv::Size(3, 3));
  cv::Point best;
  cv::minMaxLoc(smooth, nullptr, nullptr, nullptr, &best);
  bx = patch.x + best.x;
  by = patch.y + best.y;
}

}  // namespace

GridEstimate EstimateLensletGrid(const cv::Mat& grey_white, const GridGuess& guess,
                                 const GridEstimateOptions& options) {
  if (grey_white.type() != CV_32FC1 || grey_white.empty())
    throw Error("lenslet grid: the white image must be a non-empty single-channel float image");
  if (!(guess.spacing >= 3.0 && guess.spacing <= 200.0))
    throw Error("lenslet grid: initial spacing guess " + std::to_string(guess.spacing) + " px is out of range");
  if (grey_white.cols < 8 * guess.spacing || grey_white.rows < 8 * guess.spacing)
    throw Error("lenslet grid: the white image is smaller than 8 micro-lenses across");

  // 1. Lock onto one micro-image near the optical axis (clamped onto the sensor).
  const double margin = guess.spacing * 2.0;
  const double axis_x = std::clamp(guess.axis_x, margin, grey_white.cols - 1.0 - margin);
  const double axis_y = std::clamp(guess.axis_y, margin, grey_white.rows - 1.0 - margin);
  HexLattice lattice;
  lattice.rotation = guess.rotation;
  lattice.spacing_x = guess.spacing;
  lattice.spacing_y = guess.spacing * kHalfSqrt3 * guess.scale_y;
  BrightestNear(grey_white, axis_x, axis_y, guess.spacing, lattice.origin_x, lattice.origin_y);
  double brightness = 0.0;
  if (!RefineCentre(grey_white, options.window_radius * guess.spacing, 20, 0.5 * guess.spacing, lattice.origin_x,
                    lattice.origin_y, brightness))
    throw Error("lenslet grid: no micro-image found near the optical axis");

  // 2. Grow the fit from there: each stage's lattice predicts the next, wider stage well within a window.
  std::vector<Measurement> measurements;
  for (const int reach : {3, 12, 48, -1}) measurements = MeasureAndFit(grey_white, options, reach, lattice);

  // 3. Index as the camera does (lens nearest the optical axis in an unshifted row, lens (0, 0) top-left).
  LensletGrid grid = GridFromLattice(lattice, guess.axis_x, guess.axis_y, grey_white.cols, grey_white.rows);

  GridEstimate estimate;
  double sum_squares = 0.0;
  for (const Measurement& m : measurements) {
    MeasuredCentre centre;
    double lx = 0.0, ly = 0.0;
    lattice.Centre(m.i, m.j, lx, ly);
    grid.Nearest(lx, ly, centre.i, centre.j);
    centre.x = m.x;
    centre.y = m.y;
    centre.inlier = m.inlier;
    if (m.inlier) {
      sum_squares += (m.x - lx) * (m.x - lx) + (m.y - ly) * (m.y - ly);
      ++grid.lenses_used;
    }
    estimate.centres.push_back(centre);
  }
  grid.fit_method = "white-image centroids";
  grid.lenses_measured = static_cast<int>(measurements.size());
  grid.rms_residual = grid.lenses_used > 0 ? std::sqrt(sum_squares / grid.lenses_used) : 0.0;
  estimate.grid = grid;
  return estimate;
}

GridEstimate FitGridOnWhiteImage(const cv::Mat& grey_white, const LytroMetadata& mla_source) {
  return EstimateLensletGrid(grey_white, GuessFromMetadata(mla_source, grey_white.cols, grey_white.rows));
}

}  // namespace lfsp::decode
