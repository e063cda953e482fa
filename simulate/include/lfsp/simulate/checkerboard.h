#pragma once

// Checkerboard light fields for calibration, rendered directly in decoded geometry through a known lenslet-camera
// ray model (Dansereau, Pizarro and Williams, CVPR 2013), so the calibration stage can be checked against ground
// truth.
//
// Ray model: a sample index n = (i, j, k, l, 1), with i, j the pixel column and row inside a view and k, l the view
// column and row (u, v in docs/DESIGN.md), maps through a 5x5 matrix H to a ray (s, t, u, v, 1) = H n in a relative
// two-plane parameterisation (metres; plane separation 1 m): the ray leaves the point (s, t, 0) of the camera frame
// with direction (u, v, 1) (x right, y down, z forward). Radial distortion with decentring then bends the direction
// only:  d = (1 + k1 r^2 + k2 r^4 + k3 r^6) * ((u, v) - b) + b,  r = |(u, v) - b|,
// which gives the physical ray direction (d, 1). This code does not depend on the calibrate stage: it is an
// independent implementation of the same model, so tests compare two implementations.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::simulate {

// Ground-truth camera in DPW form, for a decoded light field of nu x nv views of width x height pixels.
struct CheckerboardCamera {
  std::string name;  // "illum" or "f01"
  int nu = 15;
  int nv = 15;
  int width = 625;
  int height = 434;
  std::array<double, 25> h{};          // H, row-major 5x5; the centre sample maps to the ray (0, 0, 0, 0)
  std::array<double, 5> distortion{};  // k1, k2, k3, b1, b2 (LFToolbox order)
  double focal_plane = 0.25;           // m, depth at which the views have zero disparity (for poses and blur)
};

// Illum-like geometry: 15x15 views, 625x434 pixels scaled by `scale` (the angular pixel size grows as 1/scale, so
// the field of view stays the same). F01-like: `views` x `views` (9 or 11) of 380x380 pixels scaled by `scale`.
CheckerboardCamera IllumCheckerboardCamera(double scale = 1.0);
CheckerboardCamera F01CheckerboardCamera(int views = 11, double scale = 1.0);

// Rigid transform from the board frame (origin at corner (0, 0), x along a corner row, y down the columns, z into
// the board) to the camera frame: p_camera = R(rotation) p_board + translation. `rotation` is an angle-axis vector.
struct BoardPose {
  std::array<double, 3> rotation{};
  std::array<double, 3> translation{};
};

struct CheckerboardCaptureOptions {
  CheckerboardCamera camera = IllumCheckerboardCamera();
  int corners_x = 19;  // inner corners per row and per column of the board
  int corners_y = 19;
  double square_size = 3.61e-3;  // m
  BoardPose pose;
  int channels = 3;                // 3: grey replicated to RGB with independent noise; 1: grey
  double blur = 0.5;               // optical blur (Gaussian sigma, pixels) at the focal plane
  double defocus_blur = 0.35;      // extra sigma per pixel of disparity (defocus grows with the distance to focus)
  double read_noise = 0.004;       // noise standard deviation at black, in [0, 1] units
  double photons_at_white = 2500;  // shot noise: variance of a value x is x / photons_at_white
  double aperture_radius = 1.02;   // views with aperture radius (in half view-grid widths) beyond this are dark
  std::uint32_t seed = 1;
  int zoom_step = 600;  // recorded in the metadata (camera.zoom_step / focus_step), as a decoder would
  int focus_step = 430;
  std::string serial = "sim-checkerboard";
};

struct CheckerboardCapture {
  LightField light_field;  // nv x nu views, linear, values in [0, 1], per-ray weights = vignetting
  // Ground-truth corner positions per view (row-major cam = v * nu + u), corner (a, b) at index b * corners_x + a,
  // in pixels (pixel centres at integers); NaN where the corner leaves the view.
  std::vector<std::vector<PixelPosition>> corners;
  BoardPose pose;
};

CheckerboardCapture RenderCheckerboardLightField(const CheckerboardCaptureOptions& options);

// `count` diverse board poses (tilts of 15-40 degrees about varied axes, in-plane turns, distances and offsets that
// keep the whole board with its white margin inside the centre view), deterministic for a seed.
std::vector<BoardPose> CalibrationPoses(const CheckerboardCamera& camera, int count, std::uint32_t seed = 7,
                                        int corners_x = 19, int corners_y = 19, double square_size = 3.61e-3);

// Where the board point (x, y, 0) (board frame, metres) appears in view (u, v): pixel coordinates, found by
// inverting the ray model with Newton steps. Returns false if it does not converge inside the view.
bool ProjectBoardPoint(const CheckerboardCamera& camera, const BoardPose& pose, double x, double y, int u, int v,
                       PixelPosition& pixel);

}  // namespace lfsp::simulate
