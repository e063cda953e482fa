#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

// The detail band of the cost (before its contrast normalisation): the grey image (mean of RGB) minus its Gaussian
// blur of `sigma` pixels.
cv::Mat DetailHighPass(const cv::Mat& rgb, double sigma);

// The automatic CostOptions::detail_weight: how far the detail term (the normalised high-pass grey image) can be
// trusted on these views, as a Wiener-style ratio m^2 / (m^2 + (kDetailNoiseMargin * n)^2), where
//  - m is the median local RMS of the centre view's high-pass grey image, after the presmoothing the cost sees;
//  - n is what white noise of the centre view's noise floor (EstimateNoiseFloor, before smoothing) leaves in that
//    band: the floor times the norm of the band's kernel (presmoothing, then the detail high-pass).
// Why: bilinear lookups at fractional shifts average neighbouring noise samples and lower the cost there, while
// integer shifts keep it whole; where the texture is weak, the detail term then chooses a disparity by how
// fractional its shifts are. On the full-size Illum two-horses capture (background at d = -1, central 9x9, 2.5 px
// presmoothing) the detail term alone puts the background at -0.13, and the whole cost at -0.933 (BadPix 0.07
// 34.8 %) with weight 1. The decoder's own error structure in this band (demosaicking, white-image noise) is about
// sixteen times the white-noise figure n, hence the margin (chosen on that capture: weight 0.15, BadPix 11.0 %;
// the F01 capture reads 0.19, its noise-free twin 0.33, the bundled 80x60 mini-Illum decode with its strong
// pixel-scale texture 0.79). Views that are not presmoothed (clean ones) keep weight 1: on antinous the rule would
// read 0.03 and cost BadPix 0.07 5.9 -> 13.5 %.
constexpr double kDetailNoiseMargin = 16.0;
float DetailWeightFor(const cv::Mat& raw_centre, const cv::Mat& smoothed_centre, double presmooth_sigma,
                      const CostOptions& options);

}  // namespace lfsp::depth
