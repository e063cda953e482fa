#pragma once

#include "lfsp/core/light_field.h"
#include "lfsp/core/noise.h"

namespace lfsp::depth {

// The Gaussian pre-smoothing (pixels) chosen for a noise level (EstimateChannelNoiseSigma of the centre view):
// none up to kDepthCleanNoise, then 1 px per 0.001 of noise above it, capped at 2.5 px. Calibrated on full-size
// captures of fronto-parallel strips at d = -1.5 .. 1.5 decoded to their well-lit views, with sensor noise: Illum
// reads 0.0056 and needs 2-2.5 px for every strip to be within 0.02 (unsmoothed: up to 0.12 off), F01 reads 0.0052
// and needs 2-2.5 px (unsmoothed: up to 0.28 off); HCI antinous reads 0.0019 and is not smoothed.
constexpr double kDepthCleanNoise = 0.003;
double PresmoothSigmaForNoise(double noise_sigma);

// The least smoothing for views decoded from a lenslet sensor (kLensletPresmoothFloor px, when the light field's
// metadata says it was decoded; 0 otherwise). Pixel-scale noise makes the cost prefer fractional shifts, where the
// bilinear resampling of a view averages noise down, so disparities near integers are pushed off them. A decoded
// capture always carries such noise (white-image shot noise and quantisation, resampled twice), and the noise
// estimate reads it low because the resampling correlates it. Measured on full-size noise-free captures:
//  - Illum plane at d = -1, central 9x9: -1.083 unsmoothed, -0.992 at 0.8 px, -0.988 at 1.6 (ideal: -0.988); the
//    ideal light field plus white noise of 0.001 reproduces the bias (-1.086);
//  - F01 strips, central 7x7: d = +-1 read +-0.95 at 0.8 px, +-0.99 at 1.2 and 1.6 px.
// Rendered light fields (HCI) keep the noise rule alone: 0.8 px there costs antinous MSE x100 5.5 -> 11.2.
constexpr double kLensletPresmoothFloor = 1.5;
double PresmoothFloorFor(const LightField& light_field);

// The automatic presmoothing: the noise rule, at least the lenslet floor; but a decode whose texture reaches the
// pixel scale (fine_band_snr >= kFineTextureHigh, detail_weight.h) is smoothed by the floor alone, as the noise rule
// would blur its signal away with the noise: the bundled 80x60 mini-Illum decode (noise 0.033, fine_band_snr 10.4)
// reads BadPix 0.07 48.5 % at the noise rule's 2.5 px and 28.7 % at the floor's 1.5 px.
double AutomaticPresmoothSigma(const LightField& light_field, double noise_sigma, double fine_band_snr);

// The automatic CostOptions::excluded_ring: 1 for light fields decoded from a lenslet sensor that keep at least
// 5x5 views (the ring of 8 next to the centre shares its sensor pixels), else 0.
int ExcludedRingFor(const LightField& light_field);

// A copy of the light field with every view Gaussian-smoothed (sigma in pixels), in parallel over views; transfer
// and metadata are kept, per-ray weights are not.
LightField Presmoothed(const LightField& light_field, double sigma);

}  // namespace lfsp::depth
