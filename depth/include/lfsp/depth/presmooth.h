#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp::depth {

// Standard deviation of white noise in an RGB or grey image (its grey version), after Immerkaer (Fast noise
// variance estimation, CVIU 1996): the response to a 3x3 mask that cancels any plane, here its median absolute
// value, which texture inflates less than the mean. A clean view reads about 0.002-0.003 (antinous 0.002, a
// simulated Illum capture at 6300 photons at white 0.002), the same capture at 180 photons 0.022.
double EstimateNoiseSigma(const cv::Mat& image);

// The Gaussian pre-smoothing (pixels) chosen for a noise level: none up to `kNoiseFloor`, then 1 px per 0.01 of
// noise above it, capped at 2.5 px. Measured on a simulated Illum capture (planes scene) decoded to its central 9x9
// views: the disparity's mean error at 180 photons at white falls from 0.52 px unsmoothed to 0.10 px.
constexpr double kNoiseFloor = 0.004;
double PresmoothSigmaForNoise(double noise_sigma);

// A copy of the light field with every view Gaussian-smoothed (sigma in pixels), in parallel over views.
LightField Presmoothed(const LightField& light_field, double sigma);

}  // namespace lfsp::depth
