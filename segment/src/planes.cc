#include "planes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <unordered_map>

#include "lfsp/core/plane_fit.h"

namespace lfsp::segment {
namespace {

// The sums of a plane fit (lfsp/core/plane_fit.h): over a label's pixels, a boundary's points, or both.
using Moments = PlaneSums;

cv::Vec3d AsVector(const Plane& plane) { return {plane.a, plane.b, plane.c}; }

bool SolvePlane(const cv::Matx33d& m, const cv::Vec3d& r, Plane& plane) {
  cv::Vec3d abc;
  if (!lfsp::SolvePlane(m, r, abc)) return false;
  plane = {abc[0], abc[1], abc[2]};
  return true;
}

// A pixel of the centre view by its coordinates (the plane fits need x and y; dividing an index by the width was a
// third of the plane smoothing's time).
struct Pixel {
  int x, y;
};

std::vector<std::vector<Pixel>> PixelsOfLabels(const cv::Mat& labels, int count) {
  std::vector<std::vector<Pixel>> pixels(static_cast<std::size_t>(count));
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) pixels[static_cast<std::size_t>(row[x])].push_back({x, y});
  }
  return pixels;
}

// Inlier moments of one label's pixels around the current plane (all finite samples if fewer than 3 inliers).
Moments InlierMoments(const std::vector<Pixel>& pixels, const cv::Mat& disparity, const Plane& plane,
                      double threshold) {
  const int width = disparity.cols;
  const float* d = disparity.ptr<float>(0);
  Moments inliers;
  for (const Pixel& pixel : pixels) {
    const float value = d[pixel.y * width + pixel.x];
    if (!std::isfinite(value)) continue;
    const double x = pixel.x, y = pixel.y;
    if (std::abs(value - plane.AtCentre(x, y)) < threshold) inliers.Add(x, y, value);
  }
  if (inliers.n >= 3) return inliers;
  Moments all;
  for (const Pixel& pixel : pixels) {
    const float value = d[pixel.y * width + pixel.x];
    if (std::isfinite(value)) all.Add(pixel.x, pixel.y, value);
  }
  return all;
}

double MedianDisparity(const std::vector<Pixel>& pixels, const cv::Mat& disparity) {
  const float* d = disparity.ptr<float>(0);
  std::vector<float> values;
  values.reserve(pixels.size());
  const int width = disparity.cols;
  for (const Pixel& pixel : pixels) {
    const float value = d[pixel.y * width + pixel.x];
    if (std::isfinite(value)) values.push_back(value);
  }
  if (values.empty()) return 0.0;
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// One boundary between labels i < j: its half-pixel sample points (between 4-neighbours of different labels).
struct Boundary {
  int i = 0;
  int j = 0;
  Moments points;
  BoundaryType type = BoundaryType::kHinge;
};

std::vector<Boundary> FindBoundaries(const cv::Mat& labels) {
  std::unordered_map<std::uint64_t, std::size_t> index;
  std::vector<Boundary> boundaries;
  auto add = [&](int a, int b, double x, double y) {
    const int i = std::min(a, b), j = std::max(a, b);
    const std::uint64_t key = (static_cast<std::uint64_t>(i) << 32) | static_cast<std::uint32_t>(j);
    auto [it, inserted] = index.try_emplace(key, boundaries.size());
    if (inserted) boundaries.push_back({i, j, {}, BoundaryType::kHinge});
    boundaries[it->second].points.Add(x, y);
  };
  for (int y = 0; y < labels.rows; ++y) {
    const int* row = labels.ptr<int>(y);
    const int* below = y + 1 < labels.rows ? labels.ptr<int>(y + 1) : nullptr;
    for (int x = 0; x < labels.cols; ++x) {
      if (x + 1 < labels.cols && row[x + 1] != row[x]) add(row[x], row[x + 1], x + 0.5, y);
      if (below != nullptr && below[x] != row[x]) add(row[x], below[x], x, y + 0.5);
    }
  }
  return boundaries;
}

// Mean over a point set (moments) of (plane_i - plane_j)^2 and of (plane_i - plane_j).
double MeanSquaredDifference(const Moments& points, const cv::Vec3d& delta) {
  return points.n > 0 ? delta.dot(points.m * delta) / points.n : 0.0;
}
double MeanDifference(const Moments& points, const cv::Vec3d& delta) {
  if (points.n <= 0) return 0.0;
  const cv::Vec3d sums(points.m(0, 2), points.m(1, 2), points.m(2, 2));  // (sum x, sum y, n)
  return delta.dot(sums) / points.n;
}

BoundaryType CheapestType(const Boundary& boundary, const std::vector<Moments>& segment_points,
                          const std::vector<Plane>& planes, const LfspParams& params) {
  const cv::Vec3d delta =
      AsVector(planes[static_cast<std::size_t>(boundary.i)]) - AsVector(planes[static_cast<std::size_t>(boundary.j)]);
  // Occlusion with the front segment chosen to agree with the planes: larger disparity is in front, so claiming
  // the other one is "impossible" and costs more; the cheaper claim is always the consistent one.
  const double front_difference = MeanDifference(boundary.points, delta);  // mean of d_i - d_j on the boundary
  const double occlusion =
      std::min(params.occlusion_penalty + (front_difference < 0 ? params.impossible_penalty : 0.0),   // i in front
               params.occlusion_penalty + (front_difference > 0 ? params.impossible_penalty : 0.0));  // j in front
  const double hinge = params.hinge_penalty + MeanSquaredDifference(boundary.points, delta);
  Moments both = segment_points[static_cast<std::size_t>(boundary.i)];
  both.m += segment_points[static_cast<std::size_t>(boundary.j)].m;
  both.n += segment_points[static_cast<std::size_t>(boundary.j)].n;
  const double coplanar = MeanSquaredDifference(both, delta);
  if (coplanar <= hinge && coplanar <= occlusion) return BoundaryType::kCoplanar;
  if (hinge <= occlusion) return BoundaryType::kHinge;
  return BoundaryType::kOcclusion;
}

}  // namespace

std::vector<Plane> FitPlanes(const cv::Mat& labels, int count, const cv::Mat& disparity, double inlier_threshold) {
  const std::vector<std::vector<Pixel>> pixels = PixelsOfLabels(labels, count);
  std::vector<Plane> planes(static_cast<std::size_t>(count));
#pragma omp parallel for schedule(dynamic, 16)
  for (int k = 0; k < count; ++k) {
    const std::vector<Pixel>& support = pixels[static_cast<std::size_t>(k)];
    Plane plane{0.0, 0.0, MedianDisparity(support, disparity)};
    for (int round = 0; round < 3; ++round) {
      const Moments inliers = InlierMoments(support, disparity, plane, inlier_threshold);
      Plane fitted;
      if (inliers.n < 3 || !SolvePlane(inliers.m, inliers.r, fitted)) break;
      plane = fitted;
    }
    planes[static_cast<std::size_t>(k)] = plane;
  }
  return planes;
}

BoundaryTypeCounts SmoothPlanes(const cv::Mat& labels, int count, const cv::Mat& disparity, double disparity_range,
                                const LfspParams& params, std::vector<Plane>& planes) {
  const std::vector<std::vector<Pixel>> pixels = PixelsOfLabels(labels, count);
  std::vector<Moments> segment_points(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    for (const Pixel& pixel : pixels[static_cast<std::size_t>(k)])
      segment_points[static_cast<std::size_t>(k)].Add(pixel.x, pixel.y);
  }
  std::vector<Boundary> boundaries = FindBoundaries(labels);
  std::vector<std::vector<std::size_t>> boundaries_of(static_cast<std::size_t>(count));
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    boundaries_of[static_cast<std::size_t>(boundaries[b].i)].push_back(b);
    boundaries_of[static_cast<std::size_t>(boundaries[b].j)].push_back(b);
  }
  const double data_weight = params.lambda_d / (disparity_range * disparity_range);

  const int boundary_count = static_cast<int>(boundaries.size());
  std::vector<Moments> data_points(static_cast<std::size_t>(count));
  for (int round = 0; round < params.plane_iterations; ++round) {
    // The boundary types and each label's inliers depend only on the planes as the round starts (label k's own
    // plane changes only at k's turn below), so both are found in parallel before the Gauss-Seidel pass.
#pragma omp parallel
    {
#pragma omp for schedule(static)
      for (int b = 0; b < boundary_count; ++b) {
        Boundary& boundary = boundaries[static_cast<std::size_t>(b)];
        boundary.type = CheapestType(boundary, segment_points, planes, params);
      }
#pragma omp for schedule(dynamic, 16)
      for (int k = 0; k < count; ++k) {
        const std::size_t sk = static_cast<std::size_t>(k);
        data_points[sk] = InlierMoments(pixels[sk], disparity, planes[sk], params.inlier_threshold);
      }
    }
    for (int k = 0; k < count; ++k) {
      const std::size_t sk = static_cast<std::size_t>(k);
      const Moments& data = data_points[sk];
      cv::Matx33d lhs = data.m * data_weight;
      cv::Vec3d rhs = data.r * data_weight;
      for (std::size_t b : boundaries_of[sk]) {
        const Boundary& boundary = boundaries[b];
        if (boundary.type == BoundaryType::kOcclusion) continue;  // occlusions do not couple the planes
        const int other = boundary.i == k ? boundary.j : boundary.i;
        const std::size_t so = static_cast<std::size_t>(other);
        cv::Matx33d coupling;
        double weight;
        if (boundary.type == BoundaryType::kHinge) {
          coupling = boundary.points.m;
          weight = params.lambda_s / std::max(1.0, boundary.points.n);
        } else {
          coupling = segment_points[sk].m + segment_points[so].m;
          weight = params.lambda_s / std::max(1.0, segment_points[sk].n + segment_points[so].n);
        }
        lhs += coupling * weight;
        rhs += (coupling * AsVector(planes[so])) * weight;
      }
      Plane fitted;
      if (data.n >= 3 && SolvePlane(lhs, rhs, fitted)) planes[sk] = fitted;
    }
  }
  BoundaryTypeCounts counts;
  for (const Boundary& boundary : boundaries) {
    switch (CheapestType(boundary, segment_points, planes, params)) {
      case BoundaryType::kOcclusion:
        ++counts.occlusion;
        break;
      case BoundaryType::kHinge:
        ++counts.hinge;
        break;
      case BoundaryType::kCoplanar:
        ++counts.coplanar;
        break;
    }
  }
  return counts;
}

}  // namespace lfsp::segment
