#pragma once

// Figures of a decoded light field's quality that need no lenslet model: bands, and closeness to a simulated truth.
//
// How strongly a decoded view is striped by horizontal bands about 14 rows apart: what JPEG-stored F01 mosaics
// leave (jpeg_mosaic.h: 8-px block cycles sampled by lens rows 8.6 px apart). The measure of issue 49:
// the row means of a per-pixel quantity over the view, Hann-windowed, and the largest spectral amplitude at periods
// of 11-16 rows over the median amplitude at periods of 6-40 rows. Clean real decodes by other tools, and HCI
// antinous, read 1.8-2.9 on the chroma; IMG_3 of ../shared/data/lytro_raw read 9.9 as first decoded.

#include <array>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::decode {

// The band ratio of one series of row means (the periods are in rows). 0 for fewer than 48 rows.
double RowBandRatio(const std::vector<double>& row_means);

// The ratio on view `view` (RGB) of the chroma G - (R + B) / 2, and of the luminance (R + G + B) / 3, in the
// samples as stored (display-encoded for sRGB light fields).
double ChromaBandRatio(const LightField& light_field, ViewIndex view);
double LumaBandRatio(const LightField& light_field, ViewIndex view);

// How close a decode's centre view is to the truth the simulator wrote for it (ground_truth/decoded.h5), in linear
// light after one least-squares gain per channel (exposure and white balance are not errors), leaving out `border`
// pixels at each edge. The two must have the same view size.
struct CentreFidelity {
  double psnr_db = 0.0;       // over R, G and B, peak 1
  double chroma_error = 0.0;  // mean |error of G - (R + B) / 2|
  std::array<double, 3> gains = {1.0, 1.0, 1.0};
};
CentreFidelity CompareCentreWithTruth(const LightField& decoded, const LightField& truth, int border = 8);

}  // namespace lfsp::decode
