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
// a = 1/2) down to the constant; the third difference leaves the sum and the first two moments unchanged. Its third
// moment is not zero: at a = 0 the weights are (0.184, 0.615, 0.218, -0.017) and just below a = 1 their mirror, so
// the kernel jumps at whole-pixel shifts by about 0.017 times the image's third difference (zero at a = 1/2). On
// the test plane of noise_matched_kernel_test.cc this leaves -0.996 where the truth is -1.
constexpr float kNoiseMatchedGain = 1060.0f / 2304.0f;  // the cubic B-spline's gain at a = 1/2, its least

// The four weights for a in [0, 1] (a = 1, which rounding can give for a tiny negative shift, is the kernel one
// pixel on at a = 0, mirrored).
std::array<float, 4> NoiseMatchedWeights(float a);

// The centre view, which is compared at whole pixels, is blurred by the cubic B-spline at a = 0: (1, 4, 1) / 6,
// second moment 1/3 like every resampled view, so a textured surface looks the same in both up to the third moment.
constexpr std::array<float, 3> kNoiseMatchedCentreKernel = {1.0f / 6.0f, 4.0f / 6.0f, 1.0f / 6.0f};

// Keys' cubic convolution (a = -1/2) at the same four taps: exact on quadratics, so its blur's second moment is 0
// at every a.
std::array<float, 4> CubicConvolutionWeights(float a);

}  // namespace lfsp::depth
