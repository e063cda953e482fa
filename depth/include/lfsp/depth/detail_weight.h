#pragma once

#include <array>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

// The detail band of the cost (before its contrast normalisation): the grey image (mean of RGB) minus its Gaussian
// blur of `sigma` pixels.
cv::Mat DetailHighPass(const cv::Mat& rgb, double sigma);

// The automatic CostOptions::detail_weight: how far the detail term (the normalised high-pass grey image) can be
// trusted on these views.
//  - Views that are not presmoothed (clean ones) keep weight 1: on antinous a lower weight cost BadPix 0.07
//    5.9 -> 13.5 % (measured with the method of then; 5.7 % today).
//  - Rendered light fields with noise (not decoded from a sensor) keep weight 1 too: their noise is white, which the
//    presmoothing is for. Antinous plus white noise of 0.005 (then presmoothed 2.5 px, bilinear): weight 0.10 (the
//    decode rule below) BadPix 63.5 %, weight 1 37.6 %; noise 0.02: 70.6 -> 53.7 %.
//  - Light fields decoded from a lenslet sensor: a Wiener-style ratio m^2 / (m^2 + (kDetailNoiseMargin * n)^2),
//    where m is the median local RMS of the centre view's high-pass grey image after the presmoothing the cost sees
//    and n is what white noise of the centre view's noise floor (EstimateNoiseFloor, before smoothing) leaves in that
//    band (the floor times the norm of the band's kernel: presmoothing, then the detail high-pass), times
//    FineTextureShare(fine_band_snr). The decoder's own error in this band (demosaicking, the hexagonal resampling,
//    white-image noise) is not white and is shared between views: it pulls the detail term towards disparities
//    where views overlap it (the full-size Illum two-horses capture, background at d = -1, central 9x9, 2.5 px
//    presmoothing: the detail term alone puts the background at -0.13). Its level is about sixteen times the
//    white-noise figure n, hence the margin; and where the unsmoothed view's finest band is mostly that error
//    (fine_band_snr about 2.6 on the full-size Illum and F01 two-horses decodes, 3.6 on the noise-free F01 one),
//    the term is left out: F01 BadPix 0.07 55.4 -> 33.2 %, noise-free F01 13.9 -> 5.9 %, Illum 11.3 -> 8.6 % (depth
//    alone). The bundled 80x60 mini-Illum decode, whose texture reaches the pixel scale (fine_band_snr 10.4), keeps
//    its weight (0.79 -> 0.69 at the old 1.5 px of presmoothing; without the term it read 94 % instead of 29 %;
//    0.44 at kNoisyViewsPresmooth's 0.6 px, BadPix 0.07 19.8 %).
constexpr double kDetailNoiseMargin = 16.0;

// How strong the unsmoothed centre view's detail band is against what white noise of its noise floor would leave
// there (the median local RMS of DetailHighPass over the floor times the band's kernel norm): about 1 for white noise
// alone, about 3 on full-size lenslet decodes of weak textures, 10 where the scene's texture reaches the pixel scale.
double FineBandSignalToNoise(const cv::Mat& raw_centre, const CostOptions& options);

// The share of a decode's detail weight kept for its fine-band signal-to-noise ratio: none up to
// kFineTextureLow, all from kFineTextureHigh, linear between.
constexpr double kFineTextureLow = 4.0;
constexpr double kFineTextureHigh = 8.0;
double FineTextureShare(double fine_band_snr);

// The automatic CostOptions::channel_weights from the centre view's per-channel noise (EstimateNoiseSigmaPerChannel):
// on noisy views (a channel's noise above kCleanNoiseLevel) each channel's |difference| is weighted by the inverse of
// its noise variance, the three weights summing to 3; on clean views 1, 1, 1. A Lytro decode's colour matrix amplifies
// the red and blue noise several times more than the green: the full-size F01 two-horses decode reads weights
// 0.35, 2.45, 0.19, and an even sum let the noisiest channels decide weak textures (pipeline BadPix 0.07 36.7 -> 17.1
// %; inverse-noise weights 22.2 %).
std::array<float, 3> ChannelWeightsForNoise(const std::vector<double>& sigma);

float DetailWeightFor(const cv::Mat& raw_centre, const cv::Mat& smoothed_centre, double presmooth_sigma,
                      bool decoded_from_sensor, double fine_band_snr, const CostOptions& options);

}  // namespace lfsp::depth
