#pragma once

#include <vector>

#include <array>
#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"
#include "lfsp/decode/lenslet_decoder.h"
#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {

// What happens to each ray's colour on its way into the light field: out = clamp(scale * M * rgb, 0, 1), linear.
struct RayColour {
  std::array<float, 9> matrix = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major, out = M * in
  float scale = 1.0f;
};

// Sets every sample and weight of `light_field` (geometry.views^2 views of geometry.width x geometry.height, RGB, with
// weights) in one interpolation pass: for every lens row y and view (u, v), each micro-lens of the row is looked up
// once at the view's offset ((u - uc), (v - vc)) * view_step from its centre (bilinear in the sensor image), then the
// output row is interpolated along the lens row (cubic, Catmull-Rom) at lattice positions x * sqrt(3)/2: hexagonal to
// rectangular. Weights come the same way from `grey_white`, zero beyond the micro-lens radius. Each lookup keeps
// to its own micro-lens (`lens_labels`, LensLabels). `rgb` is CV_32FC3
// (demosaicked, devignetted), `grey_white` CV_32FC1, both sensor-sized. Parallel over lens rows, which keeps each
// thread's reads within a band of sensor rows.
// When `light_field` holds fewer views than the geometry (N x N of geometry.views^2), they are the central N x N.
// `discard_behind`: sensor-size images (among `rgb` and `grey_white`) the caller will not read again. As the slicing
// moves down the sensor, the pages of the rows that no lens row still to come reads are given back (DiscardPages),
// so the light field fills up while they empty (issue 46); those rows read as zero afterwards.
void SliceLensletImage(const cv::Mat& rgb, const cv::Mat& grey_white, const cv::Mat& lens_labels,
                       const LensletGrid& grid, const DecodedGeometry& geometry, const RayColour& colour,
                       LightField& light_field, const std::vector<cv::Mat*>& discard_behind = {});

// Every view's mean weight as the slicing would give it, estimated from the white image alone (bilinear at each
// lens of every fourth lens row, without the cubic along the rows or the taps under other lenses): a few
// milliseconds, to choose which views to slice. Camera order (v * views + u).
std::vector<double> ApproximateViewMeanWeights(const cv::Mat& grey_white, const LensletGrid& grid,
                                               const DecodedGeometry& geometry);

// The level of the brightest rays: the 99.99th percentile of the largest channel of M * rgb over the well-lit
// sensor pixels (grey white >= 0.5), so a scale that keeps highlights unclipped can be chosen before slicing
// without a few noise outliers setting it.
float BrightestWellLit(const cv::Mat& rgb, const cv::Mat& grey_white, const std::array<float, 9>& matrix);

// Softens what hexagonal sampling leaves behind: along vertical edges, shifted and unshifted lens rows place the edge
// half a pitch apart, so the decoded view alternates row by row. Each row is mixed with its two neighbours,
// [alpha, 1 - 2 alpha, alpha] (the response at the row-alternation frequency is 1 - 4 alpha). In the same pass, the
// linear values are sRGB-encoded if `srgb`. Parallel over views.
void SoftenAndEncode(LightField& light_field, float alpha, bool srgb);

}  // namespace lfsp::decode
