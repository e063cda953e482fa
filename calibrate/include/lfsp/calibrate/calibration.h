#pragma once

// Checkerboard calibration of a lenslet camera (Dansereau, Pizarro and Williams, CVPR 2013).
//
// Pipeline: corners in every view of every capture (corners.h) -> initialisation from homographies -> Ceres
// refinement in three stages, as LFToolbox does:
//   no-distortion   the eight slopes of H and one pose per capture, distortion held at zero;
//   with-distortion the same plus k1, k2, k3, b1, b2;
//   refine          all parameters again on the observations that survive outlier rejection, with a Huber loss
//                   scaled to the previous stage's error.
// The cost of one observed corner is the 3-D distance (mm) between the corner, moved into the camera frame by its
// capture's pose, and the physical ray of the sample index where it was seen. The problem is sparse: each pose
// links only to its own capture's observations plus the shared intrinsics and distortion.
//
// Gauge: H11 and H22 (the s-plane position's dependence on the pixel index) are held at zero. Without distortion,
// moving the s, t plane along z changes (H11, H13) and every pose's z translation together without changing a
// single residual, so they cannot be estimated; zero places the s, t plane where each view is an exact pinhole
// camera (the main-lens aperture). The offsets H15..H45 are fixed by recentring (ray_model.h).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/calibrate/corners.h"
#include "lfsp/calibrate/ray_model.h"

namespace lfsp::calibrate {

struct CalibrationOptions {
  double square_size = 3.61e-3;  // m, checker square side
  int min_captures = 3;          // fewer usable captures -> lfsp::Error (10 or more recommended: a warning below)
  int recommended_captures = 10;
  int min_views_per_capture = 5;      // a capture with fewer views with corners is dropped, with a warning
  bool allow_mixed_settings = false;  // captures at different zoom/focus steps or from different cameras: warning
                                      // instead of an error
  int max_iterations = 100;           // per stage
  double outlier_threshold = 5.0;     // refine stage: drop observations beyond this many times the RMS error
  double huber_scale = 2.0;           // refine stage: Huber loss scale, in multiples of the RMS error
  int view_stride = 2;                // the first two stages use every view_stride-th view (u and v); refine uses all
  int threads = 0;                    // 0: OpenMP's default
};

struct CapturePose {
  std::string name;
  std::array<double, 3> rotation{};     // angle-axis, board -> camera
  std::array<double, 3> translation{};  // m
  double rms_mm = 0;                    // RMS ray reprojection error of this capture's observations
  int observations = 0;                 // corners used in the final stage
  std::vector<ViewIndex> views;         // views whose corners were used
  std::vector<ViewIndex> dark_views;    // skipped for low weight
  std::vector<ViewIndex> edge_views;    // skipped at the lenslet's edge (CornerDetectionOptions::view_border)
  std::vector<ViewIndex> failed_views;  // bright enough, but the board was not tracked there
};

struct StageReport {
  std::string name;  // "initial", "no-distortion", "with-distortion", "refine"
  double rms_mm = 0;
  int iterations = 0;
  int observations = 0;
  double seconds = 0;
};

struct Calibration {
  LightFieldShape shape;  // the decoded geometry the model belongs to (channels unused)
  RayModel model;
  int corners_x = 0;
  int corners_y = 0;
  double square_size = 0;
  std::string camera_model;
  std::string serial;
  std::optional<int> zoom_step;
  std::optional<int> focus_step;
  std::vector<CapturePose> captures;
  std::vector<std::string> rejected_captures;  // "name: reason"
  std::vector<StageReport> stages;
  std::vector<std::string> warnings;
  double rms_mm = 0;  // overall RMS ray reprojection error (final stage)
};

// Calibrates from the corners of several captures of the same camera at the same zoom and focus. Throws
// lfsp::Error (naming the captures concerned) for mismatched light-field sizes or grids, mixed zoom/focus steps
// (unless allowed) and too few usable captures.
Calibration Calibrate(const std::vector<CaptureCorners>& captures, const CalibrationOptions& options = {});

// The 3-D distance (m) between board point (x, y, 0) and the physical ray of sample index (i, j, k, l) for a
// capture pose: the quantity the calibration minimises, exposed for tests and reports.
double RayDistance(const RayModel& model, const std::array<double, 3>& rotation,
                   const std::array<double, 3>& translation, double i, double j, double k, double l, double x,
                   double y);

}  // namespace lfsp::calibrate
