// Calibration: 10 simulated checkerboard captures (19x19 inner corners, 3.61 mm squares) at full decoded size,
// Illum geometry (15x15 views of 625x434; issue 7 target: <= 60 s on 2 cores) and F01 geometry (11x11 of
// 380x380). The timed run is what `lfsp calibrate` does after loading: corners in every view of every capture,
// then the three solver stages. The quality figure compares the result with the simulator's ground truth.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_case.h"
#include "lfsp/calibrate/calibration.h"
#include "lfsp/calibrate/corners.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/simulate/checkerboard.h"

namespace lfsp::bench {
namespace {

struct CalibrationData {
  simulate::CheckerboardCamera camera;
  std::vector<LightField> captures;
};

// Grey captures (one channel) keep the ten full-size light fields at 4.9 GB with their weights.
std::shared_ptr<CalibrationData> Render(const simulate::CheckerboardCamera& camera) {
  auto data = std::make_shared<CalibrationData>();
  data->camera = camera;
  const auto poses = simulate::CalibrationPoses(camera, 10, 7);
  for (std::size_t n = 0; n < poses.size(); ++n) {
    simulate::CheckerboardCaptureOptions options;
    options.camera = camera;
    options.pose = poses[n];
    options.channels = 1;
    options.seed = 500 + static_cast<std::uint32_t>(n);
    data->captures.push_back(simulate::RenderCheckerboardLightField(options).light_field);
  }
  return data;
}

// Largest difference between the calibrated and the true physical ray directions over the observed corners (every
// 7th of every view), in pixels, after removing the mean (a common rotation the poses absorb): how well the
// distortion is recovered where the board was seen.
double RayFieldError(const calibrate::RayModel& model, const simulate::CheckerboardCamera& camera,
                     const std::vector<calibrate::CaptureCorners>& corners) {
  calibrate::RayModel truth;
  for (int r = 0; r < 5; ++r)
    for (int c = 0; c < 5; ++c) truth.H(r, c) = camera.h[static_cast<std::size_t>(5 * r + c)];
  truth.distortion = calibrate::Distortion::FromArray(camera.distortion);
  std::vector<std::array<double, 2>> diff;
  double mu = 0, mv = 0;
  for (const auto& capture : corners)
    for (const auto& view : capture.views)
      for (std::size_t n = 0; n < view.corners.size(); n += 7) {
        const auto a = model.PhysicalRay(view.corners[n].x, view.corners[n].y, view.view.u, view.view.v);
        const auto b = truth.PhysicalRay(view.corners[n].x, view.corners[n].y, view.view.u, view.view.v);
        diff.push_back({a.u - b.u, a.v - b.v});
        mu += a.u - b.u;
        mv += a.v - b.v;
      }
  mu /= static_cast<double>(diff.size());
  mv /= static_cast<double>(diff.size());
  double worst = 0;
  for (const auto& d : diff) worst = std::max(worst, std::hypot(d[0] - mu, d[1] - mv));
  return worst / truth.H(2, 0);
}

std::string Calibrate(const CalibrationData& data) {
  const Stopwatch stopwatch;
  std::vector<calibrate::CaptureCorners> corners;
  for (std::size_t n = 0; n < data.captures.size(); ++n)
    corners.push_back(calibrate::DetectCaptureCorners(data.captures[n], "capture" + std::to_string(n)));
  const double detect = stopwatch.Seconds();
  const calibrate::Calibration result = calibrate::Calibrate(corners);
  const calibrate::Slopes est = result.model.GetSlopes();
  const auto& h = data.camera.h;
  const double truth[8] = {h[0], h[2], h[10], h[12], h[6], h[8], h[16], h[18]};
  double worst = 0;
  for (int n = 0; n < 8; ++n)
    if (truth[n] != 0)
      worst = std::max(worst, std::abs(est[static_cast<std::size_t>(n)] - truth[n]) / std::abs(truth[n]));
  char text[240];
  std::snprintf(
      text, sizeof text,
      "RMS %.4f mm, max |dH|/H %.3f %%, k1 %.4f (true %.4f), ray field %.3f px; corners %.1f s, solver %.1f s",
      result.rms_mm, 100 * worst, result.model.distortion.k1, data.camera.distortion[0],
      RayFieldError(result.model, data.camera, corners), detect, result.stages.back().seconds);
  return text;
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "calibrate";
  c.name = "illum-10-captures";
  c.input = "10 x Illum 15x15x625x434, 19x19 corners";
  c.target = "<= 60 s";
  c.repetitions = 2;
  auto data = std::make_shared<std::shared_ptr<CalibrationData>>();
  c.prepare = [data] { *data = Render(simulate::IllumCheckerboardCamera()); };
  c.run = [data] { return Calibrate(**data); };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "calibrate";
  c.name = "f01-10-captures";
  c.input = "10 x F01 11x11x380x380, 19x19 corners";
  c.target = "-";
  c.repetitions = 2;
  auto data = std::make_shared<std::shared_ptr<CalibrationData>>();
  c.prepare = [data] { *data = Render(simulate::F01CheckerboardCamera(11)); };
  c.run = [data] { return Calibrate(**data); };
  return c;
}

}  // namespace lfsp::bench
