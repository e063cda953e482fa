#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "lfsp/simulate/lenslet_camera.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::simulate {

struct CaptureOptions {
  std::uint64_t seed = 1;
  double exposure = 0.7;      // signal (fraction of white - black) of a white surface at a micro-image centre
  int supersampling = 1;      // samples per sensor pixel along each axis (1 = one ray through the pixel centre)
  bool noise = true;          // photon shot noise + read noise
  int hot_pixels = 0;         // stuck-at-white pixels, at seeded random positions
  float disparity_scale = 1;  // multiplies the scene's disparities (pixels per decoded view step)
};

// A raw sensor image as the camera stores it (before packing), with the geometry it was rendered with.
struct RawCapture {
  int width = 0;
  int height = 0;
  std::vector<std::uint16_t> pixels;  // row-major, values in [0, 2^bits - 1]
  LensSetting setting;
  LensletLattice lattice;
  DecodedGrid grid;
  double exposure = 0;
  std::vector<std::array<int, 2>> hot_pixels;  // (x, y)
};

// The micro-image modulation (micro-lens vignetting within the disc times a gentle main-lens falloff) at sensor
// point (x, y) of lens (i, j). White images are this function (times the sensor's colour response); it is radially
// symmetric about each lens centre, so the centre is the brightest point of every micro-image.
double Modulation(const CameraModel& camera, const LensletLattice& lattice, double disc_radius, double x, double y,
                  int i, int j);

// Renders the raw capture by tracing, for each sensor pixel, the ray through its micro-lens into the scene:
// lens (i, j) gives the spatial position (decoded grid), the pixel's offset from the lens centre the view (s, t).
// Deterministic for a seed (noise comes from a counter-based generator, independent of threads).
RawCapture RenderRawCapture(const Scene& scene, const CameraModel& camera, const CaptureOptions& options);

// A white ("modulation") image at lens setting `setting_index` of camera.white_settings: a uniform white scene.
RawCapture RenderWhiteImage(const CameraModel& camera, int setting_index, std::uint64_t seed);

// Ground truth for a decoder: the ideal light field on the decoded grid (linear RGB, views x views of
// grid.width x grid.height), weights = the modulation each ray receives (0 outside the micro-image disc), centre
// disparity and labels, rendered through the same ray model as the raw capture.
RenderedLightField RenderDecodedGroundTruth(const Scene& scene, const CameraModel& camera,
                                            const CaptureOptions& options, int supersampling = 2);

}  // namespace lfsp::simulate
