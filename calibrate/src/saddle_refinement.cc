#include "saddle_refinement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace lfsp::calibrate {
namespace {

constexpr int kMaxIterations = 10;
constexpr double kConvergedPx = 1e-4;

// One step: the offset from `centre` to the stationary point of the quadratic
// a x^2 + b xy + c y^2 + d x + e y + f fitted to `blurred` around it (Gaussian weights of `sigma`). False when the
// window leaves the image or the fit has no saddle.
bool SaddleStep(const cv::Mat& blurred, const cv::Point2d& centre, double sigma, int radius, cv::Point2d& step) {
  const int x0 = static_cast<int>(std::lround(centre.x)), y0 = static_cast<int>(std::lround(centre.y));
  if (x0 - radius < 0 || y0 - radius < 0 || x0 + radius >= blurred.cols || y0 + radius >= blurred.rows) return false;
  Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  const double inv_two_sigma2 = 1.0 / (2.0 * sigma * sigma);
  for (int y = y0 - radius; y <= y0 + radius; ++y) {
    const float* row = blurred.ptr<float>(y);
    for (int x = x0 - radius; x <= x0 + radius; ++x) {
      const double dx = x - centre.x, dy = y - centre.y;
      const double w = std::exp(-(dx * dx + dy * dy) * inv_two_sigma2);
      Eigen::Matrix<double, 6, 1> f;
      f << dx * dx, dx * dy, dy * dy, dx, dy, 1.0;
      normal.noalias() += w * f * f.transpose();
      rhs.noalias() += w * static_cast<double>(row[x]) * f;
    }
  }
  const Eigen::Matrix<double, 6, 1> q = normal.ldlt().solve(rhs);
  const double a = q[0], b = q[1], c = q[2], d = q[3], e = q[4];
  const double det = 4.0 * a * c - b * b;  // Hessian determinant: negative at a saddle
  if (!(det < 0.0)) return false;
  step = {(b * e - 2.0 * c * d) / det, (b * d - 2.0 * a * e) / det};
  return std::isfinite(step.x) && std::isfinite(step.y);
}

}  // namespace

double SaddleSigma(double square_px) { return std::clamp(0.11 * square_px, 0.7, 2.5); }

int RefineCornersAtSaddles(const cv::Mat& grey, std::vector<cv::Point2d>& corners, double sigma) {
  cv::Mat blurred;
  cv::GaussianBlur(grey, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  const int radius = static_cast<int>(std::ceil(2.0 * sigma)) + 1;
  int moved = 0;
  for (auto& corner : corners) {
    cv::Point2d estimate = corner;
    bool found = false;
    for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
      cv::Point2d step;
      if (!SaddleStep(blurred, estimate, sigma, radius, step)) break;
      estimate += step;
      if (cv::norm(estimate - corner) > radius) break;  // wandered off to another feature
      if (cv::norm(step) < kConvergedPx) {
        found = true;
        break;
      }
    }
    if (found) {
      corner = estimate;
      ++moved;
    }
  }
  return moved;
}

}  // namespace lfsp::calibrate
