#pragma once

// Shared by the calibrate tests: simulated checkerboard captures (reduced sizes so the suite stays fast) and the
// comparison of a calibrated model with the simulator's ground truth.

#include <cmath>
#include <string>
#include <vector>

#include "lfsp/calibrate/calibration.h"
#include "lfsp/calibrate/corners.h"
#include "lfsp/simulate/checkerboard.h"

namespace lfsp::calibrate::testing {

struct CaptureSet {
  simulate::CheckerboardCamera camera;
  std::vector<simulate::CheckerboardCapture> captures;
  int corners_x = 0;
  int corners_y = 0;
  double square_size = 3.61e-3;
};

inline CaptureSet RenderCaptures(const simulate::CheckerboardCamera& camera, int count, int corners_x, int corners_y,
                                 std::uint32_t seed = 11, int channels = 1) {
  CaptureSet set;
  set.camera = camera;
  set.corners_x = corners_x;
  set.corners_y = corners_y;
  const auto poses = simulate::CalibrationPoses(camera, count, seed, corners_x, corners_y, set.square_size);
  for (int n = 0; n < count; ++n) {
    simulate::CheckerboardCaptureOptions options;
    options.camera = camera;
    options.corners_x = corners_x;
    options.corners_y = corners_y;
    options.square_size = set.square_size;
    options.pose = poses[static_cast<std::size_t>(n)];
    options.channels = channels;
    options.seed = seed * 100 + static_cast<std::uint32_t>(n);
    set.captures.push_back(simulate::RenderCheckerboardLightField(options));
  }
  return set;
}

inline std::vector<CaptureCorners> DetectAll(const CaptureSet& set) {
  CornerDetectionOptions options;
  options.corners_x = set.corners_x;
  options.corners_y = set.corners_y;
  std::vector<CaptureCorners> corners;
  for (std::size_t n = 0; n < set.captures.size(); ++n)
    corners.push_back(DetectCaptureCorners(set.captures[n].light_field, "capture" + std::to_string(n), options));
  return corners;
}

// The true model of the simulated camera.
inline RayModel TrueModel(const simulate::CheckerboardCamera& camera) {
  RayModel model;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) model.H(r, c) = camera.h[static_cast<std::size_t>(5 * r + c)];
  model.distortion = Distortion::FromArray(camera.distortion);
  return model;
}

// Largest difference in physical ray direction (in pixels of the true model) between two models, over the sample
// indices where corners were observed (every 7th corner of every view), after removing the mean difference (a
// common rotation of the camera frame, which the poses absorb).
inline double MaxDirectionDifferencePixels(const RayModel& a, const RayModel& b,
                                           const std::vector<CaptureCorners>& observed) {
  std::vector<std::array<double, 2>> diff;
  for (const auto& capture : observed)
    for (const auto& view : capture.views)
      for (std::size_t n = 0; n < view.corners.size(); n += 7) {
        const cv::Point2d& p = view.corners[n];
        const Ray ra = a.PhysicalRay(p.x, p.y, view.view.u, view.view.v);
        const Ray rb = b.PhysicalRay(p.x, p.y, view.view.u, view.view.v);
        diff.push_back({ra.u - rb.u, ra.v - rb.v});
      }
  double mu = 0, mv = 0;
  for (const auto& d : diff) {
    mu += d[0];
    mv += d[1];
  }
  mu /= static_cast<double>(diff.size());
  mv /= static_cast<double>(diff.size());
  double worst = 0;
  for (const auto& d : diff) worst = std::max(worst, std::hypot(d[0] - mu, d[1] - mv));
  return worst / b.H(2, 0);
}

}  // namespace lfsp::calibrate::testing
