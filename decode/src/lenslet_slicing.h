#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"
#include "lfsp/decode/lenslet_decoder.h"
#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {

// Fills `light_field` (geometry.views^2 views of geometry.width x geometry.height, RGB, with weights) in one
// interpolation pass: for output sample (u, v, x, y) the two micro-lenses of lens row y that bracket lattice position
// x * sqrt(3)/2 are looked up at the view's offset ((u - uc), (v - vc)) * view_step from their centres (bilinear in
// the sensor image), and blended linearly along the row. Weights come the same way from `grey_white`.
// `rgb` is CV_32FC3 (demosaicked, devignetted), `grey_white` CV_32FC1, both sensor-sized. Parallel over lens rows,
// which keeps each thread's reads within a band of sensor rows.
void SliceLensletImage(const cv::Mat& rgb, const cv::Mat& grey_white, const LensletGrid& grid,
                       const DecodedGeometry& geometry, LightField& light_field);

// Softens what hexagonal sampling leaves behind: along vertical edges, shifted and unshifted lens rows place the edge
// half a pitch apart, so the decoded view alternates row by row. Each row is mixed with its two neighbours,
// [alpha, 1 - 2 alpha, alpha] (the response at the row-alternation frequency is 1 - 4 alpha). Parallel over views.
void SoftenRowAlternation(LightField& light_field, float alpha);

}  // namespace lfsp::decode
