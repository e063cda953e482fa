#include "lfsp/depth/textureless_fill.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/ordered_reduction.h"

namespace lfsp::depth {

namespace {

// Grids smaller than this are solved on one thread: a coarse level's work is too little to pay for waking a second
// one several times per step.
constexpr std::size_t kParallelNodes = 1 << 16;

// A 4-neighbour least-squares problem on a grid: minimise sum_i data_i (x_i - target_i)^2 + sum over neighbours of
// right_i (x_i - x_right)^2 + down_i (x_i - x_below)^2. `weighted_target` holds data_i * target_i.
struct GridProblem {
  int width = 0;
  int height = 0;
  std::vector<double> data;
  std::vector<double> weighted_target;
  std::vector<double> right;  // to (x + 1, y); 0 in the last column
  std::vector<double> down;   // to (x, y + 1); 0 in the last row
  // Per node: whether the pixels it stands for are joined by nonzero weights inside it. A coarse node across a depth
  // step holds the mean of both sides, which is no start for either.
  std::vector<unsigned char> joined;

  std::size_t Size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
};

// out = A v, A being the problem's normal matrix (symmetric positive definite when some data_i > 0 in every
// connected part).
void Apply(const GridProblem& p, const std::vector<double>& v, std::vector<double>& out) {
#pragma omp parallel for schedule(static) if (p.Size() >= kParallelNodes)
  for (int y = 0; y < p.height; ++y) {
    for (int x = 0; x < p.width; ++x) {
      const std::size_t i = p.Index(x, y);
      double sum = p.data[i] * v[i];
      if (x + 1 < p.width) sum += p.right[i] * (v[i] - v[i + 1]);
      if (x > 0) sum += p.right[i - 1] * (v[i] - v[i - 1]);
      if (y + 1 < p.height) sum += p.down[i] * (v[i] - v[i + p.width]);
      if (y > 0) sum += p.down[i - p.width] * (v[i] - v[i - p.width]);
      out[i] = sum;
    }
  }
}

// The sum of a[i] b[i], in a fixed order of rows (OrderedParallelSum), so that it does not depend on the threads.
double Dot(const GridProblem& p, const std::vector<double>& a, const std::vector<double>& b) {
  const auto add_row = [&](int y, double& sum) {
    const std::size_t begin = p.Index(0, y), end = begin + static_cast<std::size_t>(p.width);
    for (std::size_t i = begin; i < end; ++i) sum += a[i] * b[i];
  };
  if (p.Size() < kParallelNodes) {
    double sum = 0.0;
    for (int y = 0; y < p.height; ++y) add_row(y, sum);
    return sum;
  }
  return OrderedParallelSum(
      p.height, [] { return 0.0; }, add_row, [](double& into, double from) { into += from; });
}

// Conjugate gradients with the diagonal as preconditioner, from `solution`, until no update moves a value by more
// than `tolerance` or after `iterations` steps.
void SolveConjugateGradients(const GridProblem& p, std::vector<double>& solution, int iterations, double tolerance) {
  const std::size_t n = p.Size();
  std::vector<double> inverse_diagonal(n);
  for (int y = 0; y < p.height; ++y) {
    for (int x = 0; x < p.width; ++x) {
      const std::size_t i = p.Index(x, y);
      double diagonal = p.data[i];
      if (x + 1 < p.width) diagonal += p.right[i];
      if (x > 0) diagonal += p.right[i - 1];
      if (y + 1 < p.height) diagonal += p.down[i];
      if (y > 0) diagonal += p.down[i - p.width];
      inverse_diagonal[i] = diagonal > 0.0 ? 1.0 / diagonal : 0.0;
    }
  }
  std::vector<double> residual(n), direction(n), preconditioned(n), product(n);
  Apply(p, solution, product);
  for (std::size_t i = 0; i < n; ++i) {
    residual[i] = p.weighted_target[i] - product[i];
    preconditioned[i] = inverse_diagonal[i] * residual[i];
  }
  direction = preconditioned;
  double rho = Dot(p, residual, preconditioned);
  for (int k = 0; k < iterations && rho > 0.0; ++k) {
    Apply(p, direction, product);
    const double curvature = Dot(p, direction, product);
    if (!(curvature > 0.0)) break;
    const double alpha = rho / curvature;
    double largest_step = 0.0;
#pragma omp parallel for reduction(max : largest_step) schedule(static) if (n >= kParallelNodes)
    for (std::size_t i = 0; i < n; ++i) {
      solution[i] += alpha * direction[i];
      residual[i] -= alpha * product[i];
      preconditioned[i] = inverse_diagonal[i] * residual[i];
      largest_step = std::max(largest_step, std::abs(alpha * direction[i]));
    }
    if (largest_step < tolerance) break;
    const double next_rho = Dot(p, residual, preconditioned);
    const double beta = next_rho / rho;
    rho = next_rho;
#pragma omp parallel for schedule(static) if (n >= kParallelNodes)
    for (std::size_t i = 0; i < n; ++i) direction[i] = preconditioned[i] + beta * direction[i];
  }
}

// The problem on a grid of half the size: each coarse node is a 2 x 2 block (one column or row at an odd edge).
// Data terms add; the weight between two blocks is half the fine weights that cross from one to the other, so that a
// plane costs the same on both grids (a coarse pair's step is twice a fine pair's, four times its square, and there
// are a quarter as many pairs).
GridProblem Coarsen(const GridProblem& fine) {
  GridProblem coarse;
  coarse.width = (fine.width + 1) / 2;
  coarse.height = (fine.height + 1) / 2;
  const std::size_t n = coarse.Size();
  coarse.data.assign(n, 0.0);
  coarse.weighted_target.assign(n, 0.0);
  coarse.right.assign(n, 0.0);
  coarse.down.assign(n, 0.0);
  coarse.joined.assign(n, 1);
  for (int y = 0; y < fine.height; ++y) {
    for (int x = 0; x < fine.width; ++x) {
      const std::size_t i = fine.Index(x, y);
      const std::size_t c = coarse.Index(x / 2, y / 2);
      coarse.data[c] += fine.data[i];
      coarse.weighted_target[c] += fine.weighted_target[i];
      if (x % 2 == 1 && x + 1 < fine.width) coarse.right[c] += 0.5 * fine.right[i];
      if (y % 2 == 1 && y + 1 < fine.height) coarse.down[c] += 0.5 * fine.down[i];
      const bool cut_inside = (x % 2 == 0 && x + 1 < fine.width && fine.right[i] == 0.0) ||
                              (y % 2 == 0 && y + 1 < fine.height && fine.down[i] == 0.0);
      if (!fine.joined[i] || cut_inside) coarse.joined[c] = 0;
    }
  }
  // A node across a cut would tie the two sides together again on this level: it is left out of it.
  for (int y = 0; y < coarse.height; ++y) {
    for (int x = 0; x < coarse.width; ++x) {
      const std::size_t c = coarse.Index(x, y);
      if (coarse.joined[c]) continue;
      coarse.right[c] = coarse.down[c] = 0.0;
      if (x > 0) coarse.right[c - 1] = 0.0;
      if (y > 0) coarse.down[c - coarse.width] = 0.0;
    }
  }
  return coarse;
}

// Coarse to fine: the coarsest grid (at most 16 nodes on a side) solved until no step moves a value by more than
// `tolerance`, every finer one started from the coarser solution (each block's value for its pixels) and refined by
// at most 60 steps, so that the long-range part of the solution does not have to travel pixel by pixel.
// Only the nodes whose data weight is low (below half of what `pixels_per_node` fully textured pixels weigh; nodes at
// an odd edge stand for fewer) take the block's value: the others are held by their own estimate already.
void SolveMultilevel(const GridProblem& p, std::vector<double>& solution, double tolerance,
                     double pixels_per_node = 1.0) {
  constexpr int kCoarsestSide = 16;
  constexpr int kIterationsPerLevel = 60;
  if (p.width > kCoarsestSide && p.height > kCoarsestSide) {
    const GridProblem coarse = Coarsen(p);
    // The coarse start: each block's mean (a block at an odd edge holds one or two nodes).
    std::vector<double> coarse_solution(coarse.Size(), 0.0), members(coarse.Size(), 0.0);
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        coarse_solution[coarse.Index(x / 2, y / 2)] += solution[p.Index(x, y)];
        members[coarse.Index(x / 2, y / 2)] += 1.0;
      }
    for (std::size_t c = 0; c < coarse.Size(); ++c) coarse_solution[c] /= members[c];
    SolveMultilevel(coarse, coarse_solution, tolerance, 4.0 * pixels_per_node);
    for (int y = 0; y < p.height; ++y)
      for (int x = 0; x < p.width; ++x) {
        const std::size_t block = coarse.Index(x / 2, y / 2);
        if (p.data[p.Index(x, y)] < 0.5 * pixels_per_node && coarse.joined[block])
          solution[p.Index(x, y)] = coarse_solution[block];
      }
    SolveConjugateGradients(p, solution, kIterationsPerLevel, tolerance);
  } else {
    SolveConjugateGradients(p, solution, static_cast<int>(p.Size()), tolerance);
  }
}

// How much of each pixel's own disparity the fill keeps: e / (e + scale^2), e being the squared colour gradient
// (central differences, summed over channels; 0 at the picture's border) averaged over 3 x 3. A pixel whose colour
// is not finite keeps its disparity whole.
std::vector<double> TextureWeights(const cv::Mat& guide_rgb, float texture_scale) {
  cv::Mat gx, gy;
  cv::Sobel(guide_rgb, gx, CV_32F, 1, 0, 1, 0.5);  // kernel size 1: (-1, 0, 1) / 2, the border mirrored
  cv::Sobel(guide_rgb, gy, CV_32F, 0, 1, 1, 0.5);
  const cv::Mat squared = gx.mul(gx) + gy.mul(gy);
  cv::Mat energy;
  cv::transform(squared, energy, cv::Matx13f(1.0f, 1.0f, 1.0f));  // summed over channels
  cv::blur(energy, energy, cv::Size(3, 3));
  const double scale2 = static_cast<double>(texture_scale) * texture_scale;
  std::vector<double> weights(energy.total());
  for (int y = 0; y < energy.rows; ++y)
    for (int x = 0; x < energy.cols; ++x) {
      const double e = energy.at<float>(y, x);
      weights[static_cast<std::size_t>(y) * static_cast<std::size_t>(energy.cols) + static_cast<std::size_t>(x)] =
          std::isfinite(e) ? e / (e + scale2) : 1.0;
    }
  return weights;
}

}  // namespace

void FillTexturelessDisparity(DisparityMap& disparity, const cv::Mat& guide_rgb,
                              const TexturelessFillOptions& options) {
  if (!(options.smoothness > 0.0f) || disparity.empty()) return;
  const int width = disparity.width(), height = disparity.height();
  if (guide_rgb.type() != CV_32FC3 || guide_rgb.rows != height || guide_rgb.cols != width)
    throw Error("depth: the textureless fill's guide must be a CV_32FC3 image of the disparity's size");
  GridProblem p;
  p.width = width;
  p.height = height;
  // A floor under the data weight keeps every part of the grid tied to its own estimate, however cut off.
  constexpr double kDataFloor = 1e-6;
  p.data = TextureWeights(guide_rgb, options.texture_scale);
  p.weighted_target.resize(p.Size());
  p.right.assign(p.Size(), 0.0);
  p.down.assign(p.Size(), 0.0);
  p.joined.assign(p.Size(), 1);
  // Neighbours are mixed unless the disparity steps between them: a depth edge with no colour edge (two objects of
  // one colour) stays. Colour edges need no weight of their own: their pixels are textured, so they keep their
  // disparity (weighting by colour similarity changed no figure of BENCHMARKS.md's scenes).
  // A pair with a non-finite disparity fails the test too: such a pixel is an island, solved at 0 and left as it was.
  const auto weight = [&](float a, float b) { return std::abs(a - b) <= options.jump ? options.smoothness : 0.0f; };
  std::vector<double> solution(p.Size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = p.Index(x, y);
      const float d = disparity.at(y, x);
      solution[i] = std::isfinite(d) ? d : 0.0;
      p.data[i] += kDataFloor;
      p.weighted_target[i] = p.data[i] * solution[i];
      if (x + 1 < width) p.right[i] = weight(d, disparity.at(y, x + 1));
      if (y + 1 < height) p.down[i] = weight(d, disparity.at(y + 1, x));
    }
  }
  constexpr double kTolerance = 1e-5;  // px per view step, the largest update at which a level stops
  SolveMultilevel(p, solution, kTolerance);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (std::isfinite(disparity.at(y, x))) disparity.at(y, x) = static_cast<float>(solution[p.Index(x, y)]);
}

}  // namespace lfsp::depth
