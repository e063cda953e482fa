#pragma once

#include "lfsp/core/hex_lattice.h"
#include "lfsp/core/light_field.h"

namespace lfsp::decode {

// What a JPEG-stored mosaic leaves in the decoded views as a gain. The quantization error of each 8 x 8 block depends
// on where the micro-images fall in it, so a view's sample reads brighter or darker, and its colour shifts, by where
// its sensor position falls down the block (the JPEG restoration takes out the worst of the colour, not this). Lens
// rows 8.6 px apart meet the 8-px blocks at a phase that drifts through a cycle every 13-14 rows: bands in every
// view. FlattenJpegBlockGain measures, per lit view and channel, the view over its own local mean (a blur over
// 6 rows, wider than half a cycle) averaged over the pixels whose samples fall in each of 32 bins of the block's
// height, and divides it out; three rounds, each on the last one's result. Not by brightness class as well: a
// class chosen by the local mean holds the pixels darker (or brighter) than the blur, and the textured test plane's
// views changed by 11 % rms. The scene does not line up with the bins
// (they cycle every 13-14 rows and drift along each row), so it averages away, unless its texture near the beat is
// strong; a grating at the beat's own frequency and tilt could not be told from the gain. Runs on JPEG mosaics only.
struct JpegBlockGainReport {
  double rms = 0.0;  // rms of the divided gain about 1 over the bins, mean over the lit views and channels
  double max = 0.0;  // its largest deviation from 1
  int views = 0;     // lit views measured and flattened
};

// `light_field` holds linear values (before any transfer curve) on the lattice's decoded grid (DecodedGeometryFor);
// `view_step` is that geometry's sensor pixels per view; `block` the JPEG's block size in sensor pixels.
JpegBlockGainReport FlattenJpegBlockGain(LightField& light_field, const HexLattice& lattice, double view_step,
                                         int block = 8);

// How strongly view `view`'s luminance (R + G + B) / 3, in linear light, still follows where its samples fall down the
// blocks, in % of the local level: the first two harmonics, over each sample's row in the block, of the luminance's
// difference from its local mean (a blur over 6 rows and 2 columns) over that mean, away from edges (20 %). The
// scene does not follow the blocks' rows, so it averages out: a lossless decode of the simulated F01 capture reads
// 0.08, its JPEG decode 3.3 before the gain is divided out and 0.14 after. A measure apart from
// FlattenJpegBlockGain's bins, for tests and benchmarks. 0 when no pixel is lit.
double BlockRowLuminance(const LightField& light_field, ViewIndex view, const HexLattice& lattice, double view_step,
                         int block = 8);

}  // namespace lfsp::decode
