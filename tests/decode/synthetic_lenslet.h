#pragma once

#include <cstdint>

#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/lytro_metadata.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode::testing {

// A stand-alone white-image generator for grid-model tests: a hexagonal lattice of micro-images at exactly known
// centres (the lens at (axis_x, axis_y) sits in an unshifted row), each a disc with soft edges and a radial falloff,
// a gentle main-lens falloff across the sensor, the sensor's Bayer colour response, shot and read noise.
struct SyntheticCamera {
  int width = 0;
  int height = 0;
  double spacing = 0.0;   // px along a row
  double scale_y = 1.0;   // row spacing = spacing * sqrt(3)/2 * scale_y
  double rotation = 0.0;  // rad
  double axis_x = 0.0;    // px, centre of the lens nearest the optical axis
  double axis_y = 0.0;
  double disc_fraction = 0.48;  // disc radius / spacing
  RawFormat format;
  double response_r = 0.757;
  double response_b = 0.722;
  double full_well = 9000.0;  // electrons at the white level
  double read_noise = 1.5;    // DN
  bool noise = true;
  // Main-lens vignetting of the border micro-images ("cat's eye"): beyond `cats_eye_start` of the half-diagonal,
  // each disc is cut by a second disc shifted towards the sensor centre by up to `cats_eye` disc radii in the
  // corners, so their intensity centroids move off the lens centres. 0 = off.
  double cats_eye = 0.0;
  double cats_eye_start = 0.6;

  // Truth: the centre of lens (i, j) counted from the axis lens (rows with odd j shifted by +half a pitch).
  void Centre(int i, int j, double& x, double& y) const;
  void NearestCentre(double x, double y, double& cx, double& cy) const;
  // Metadata-style guess (what the camera's devices.mla would say: the true values, slightly perturbed by the
  // caller if wanted).
  GridGuess Guess() const;
};

SyntheticCamera IllumLikeCamera();  // 7728 x 5368, 10-bit GRBG, spacing 14.294
SyntheticCamera F01LikeCamera();    // 3280 x 3280, 12-bit BGGR, spacing 9.934
SyntheticCamera MiniCamera();       // 1024 x 768, Illum optics

// The modulation (0..1) at sensor point (x, y): soft-edged disc of the nearest micro-lens times main-lens falloff.
double Modulation(const SyntheticCamera& camera, double x, double y);

// A white image, raw values (black + signal * (white - black) with noise), deterministic for a seed.
RawImage RenderWhiteRaw(const SyntheticCamera& camera, double exposure, std::uint64_t seed);

}  // namespace lfsp::decode::testing
