#pragma once

#include <array>

namespace lfsp::depth {

// Sub-pixel resampling whose output noise does not depend on where between pixels the sample falls.
//
// Bilinear interpolation at a fraction a between two pixels keeps (1 - a)^2 + a^2 of white noise's variance: all of
// it at whole-pixel shifts, half at a = 1/2 (a quarter in 2-D). A cost that compares resampled views with the centre
// view is then lower at fractional shifts for the noise alone, and disparities are pushed off the values at which
// the views' shifts are whole pixels (full-size F01 two-horses: the background, at d = -1, read -0.87 with 1 px of
// presmoothing; it took 2.5 px to hide this, which blurs depth edges).
//
// The noise-matched kernel has four taps, at -1, 0, 1, 2 pixels from floor(x), for a = x - floor(x). At every a it
// sums to 1, its centroid is a, its second moment about a is 1/3 (the blur of the cubic B-spline, whatever a), and
// the sum of its squared weights (white noise's variance gain) is kNoiseMatchedGain. It is the cubic B-spline plus
// the multiple of the third difference (-1, 3, -3, 1) that brings the B-spline's gain (0.50 at a = 0, 0.46 at
// a = 1/2) down to the constant; the third difference leaves the sum and the first two moments unchanged.
constexpr float kNoiseMatchedGain = 1060.0f / 2304.0f;  // the cubic B-spline's gain at a = 1/2, its least

// The four weights for a in [0, 1).
std::array<float, 4> NoiseMatchedWeights(float a);

// The centre view, which is compared at whole pixels, is blurred by the cubic B-spline at a = 0: (1, 4, 1) / 6,
// second moment 1/3 like every resampled view, so a textured surface looks the same in both.
constexpr std::array<float, 3> kNoiseMatchedCentreKernel = {1.0f / 6.0f, 4.0f / 6.0f, 1.0f / 6.0f};

}  // namespace lfsp::depth
