#pragma once

#include "lfsp/core/hex_lattice.h"
#include "lfsp/core/light_field.h"

namespace lfsp::decode {

// What the lens lattice leaves in a decoded view as a gain. Each decoded pixel (x, y) is sampled at x * sqrt(3)/2
// pitches along lens row y (mostly from the nearest lens there), and every error of the devignetting that depends on
// the offset within a micro-image (a white image estimated from the capture, a white image taken at another zoom or
// focus) comes back in it as a function of where that lens centre falls on the sensor's 2 x 2 Bayer tile: the same in
// every view, so depth reads it as texture at disparity 0. FlattenLatticeGain measures that function in each lit view
// (the view over its own blur across rows, averaged over the pixels whose lens centres fall in each of 16 x 16 bins
// of the tile, away from edges) and divides it out. The scene's own texture does not line up with the bins (they
// change every lens row and cycle along a row every 28 lenses on an F01, 7 on an Illum), so it averages away.
struct LatticeGainReport {
  double rms = 0.0;  // rms of the measured gain about 1 over the bins, mean over the lit views (before division)
  double max = 0.0;  // its largest deviation from 1 over the lit views
  int views = 0;     // lit views measured and flattened
};

// `light_field` holds linear values (before any transfer curve) on the lattice's decoded grid (DecodedGeometryFor).
LatticeGainReport FlattenLatticeGain(LightField& light_field, const HexLattice& lattice);

}  // namespace lfsp::decode
