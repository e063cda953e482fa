#pragma once

#include "lfsp/core/light_field.h"
#include "lfsp/core/noise.h"
#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

// The automatic choices that follow the views' noise. Views are noisy when they were decoded from a lenslet sensor
// (the metadata says so: a decode always carries pixel-scale noise, white-image shot noise and quantisation resampled
// twice, which the noise estimate reads low because the resampling correlates it) or when the centre view's estimated
// noise (EstimateChannelNoiseSigma) is above kDepthCleanNoise (HCI antinous reads 0.0019).
constexpr double kDepthCleanNoise = 0.003;
bool NoisyViews(const LightField& light_field, double noise_sigma);

// The automatic CostOptions::sampler: noise-matched on noisy views, bilinear on clean ones, whose fine texture the
// noise-matched kernel's blur would soften (HCI antinous: BadPix 0.07 / MSE x100 5.7 / 5.4 bilinear, 5.4 / 9.5
// noise-matched). It takes the median's estimate (EstimateChannelNoiseSigma), which a clean view's fine sharp
// texture raises too, and such texture wants the noise-matched kernel as well: bilinear resampling, whose blur
// varies with the sub-pixel shift, reads the simulator's noise-free layers scene's 8 px checker 0.038 px near
// (BadPix 0.07 5.27 % against 2.58 % noise-matched, both unsmoothed).
Sampler AutomaticSampler(const LightField& light_field, double noise_sigma);

// The automatic Gaussian pre-smoothing, pixels: kNoisyViewsPresmooth on noisy views, none on clean ones. It takes the
// lower quartile's estimate (EstimateChannelNoiseSigmaLowerQuartile), which that texture does not raise: smoothing a
// noise-free view only blurs its thin structures (layers: 2.89 / 2.56 smoothed by 0.6 px, 2.58 / 1.95 not). With the
// noise-matched sampler noise no longer biases the cost, so smoothing only trades noise for resolution, and little
// is best at every noise level measured (BadPix 0.07, presmoothing 0 / 0.6 / 1.0 / 1.5 / 2.5 px):
//  - HCI antinous plus white noise 0.005: 9.9 / 10.2 / 11.9 / 17.1 / 38.0 %; 0.01: 14.5 / 13.8 / 15.0 / 20.8 /
//    45.5 %; 0.04: - / 35.5 / 36.2 / 38.7 / 58.1 % (the old rule, bilinear at about 2.4, 2.5 and 2.5 px, read
//    36.7, 44.8 and 60.7 % at these three noise levels);
//  - full-size F01 two-horses capture, central 7x7, ring 2 left out: 0.6 px 4.9 %, 0.8 px 5.0 %, 1.0 px 5.1 %;
//    Illum, central 9x9: 0.6 px 2.0 %, 0.8 px 2.1 %.
// Without any smoothing the detail term (kept whole on unsmoothed views) locks onto a decode's lattice residue.
// Superpixels would take more in heavy noise: the low-light noise study (full-size Illum captures at exposures 0.7 /
// 0.06 / 0.02, noise 0.013 / 0.043 / 0.075) reads LFSP self-similarity 0.669 / 0.871 / 1.064 px at 0.6 px and 0.669
// / 0.860 / 0.981 px with 35 px per unit of noise above 0.02 added (at most 2.5 px), but depth itself was worse with
// that (the planes scene plus noise 0.06: mean |error| 0.088 at 0.6 px, 0.101 at 2.2 px), so depth keeps 0.6 px.
constexpr double kNoisyViewsPresmooth = 0.6;
double AutomaticPresmoothSigma(const LightField& light_field, double noise_sigma);

// The automatic CostOptions::excluded_ring for light fields decoded from a lenslet sensor, whose neighbouring views
// are neighbouring sensor pixels (about 1 px apart on Illum and F01) mixed by demosaicking and the sub-pixel lookup.
// The noise of a full-size F01 decode of a grey plane correlates with the centre view's by 0.64 (views one step away
// along an axis), 0.41 (diagonal), 0.20 (two steps along an axis), 0.12 (two and one), 0.03 or less beyond; at zero
// shift that shared noise draws every disparity towards 0. Ring 2 is left out when at least 7x7 views remain (F01
// two-horses capture: BadPix 0.07 7.5 -> 4.9 %; Illum 2.5 -> 2.0 %), ring 1 with 5x5, none otherwise or on rendered
// light fields.
int ExcludedRingFor(const LightField& light_field);

// One view Gaussian-smoothed (sigma in pixels, reflected borders) into `out`: what every view is matched as
// (CostOptions::presmooth_sigma, applied as the cost volume's features are made, so that no smoothed copy of the
// whole light field is held) and what the steps that read the centre view see.
void PresmoothView(const cv::Mat& view, double sigma, cv::Mat& out);

}  // namespace lfsp::depth
