#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

namespace lfsp {

// Standard deviation of white noise in an RGB or grey image (its grey version; sample units), after Immerkaer (Fast
// noise variance estimation, CVIU 1996): the response to a 3x3 mask that cancels any plane, here its median absolute
// value, which texture inflates less than the mean. A clean view reads about 0.002-0.003 (antinous 0.003, a
// simulated Illum capture at 6300 photons at white 0.002), the same capture at 180 photons 0.022 (figures from
// before decodes applied the colour matrix in linear mode). Segmentation uses it to decide how much to smooth noisy
// views; depth uses EstimateChannelNoiseSigma below.
double EstimateNoiseSigma(const cv::Mat& image);

// The same estimate on each channel of an RGB image, the largest of the three. A colour matrix with large
// off-diagonal terms (a Lytro decode's) amplifies the noise of each channel but largely cancels it in their mean,
// so the grey estimate reads a noisy decode low: a full-size F01 capture reads 0.0018 grey, 0.0052 here, its true
// per-channel noise being 0.011-0.027 (spatially correlated by resampling, which the 3x3 mask sees only in part).
double EstimateChannelNoiseSigma(const cv::Mat& rgb);
// The per-channel estimates themselves, one per channel of the image (what EstimateChannelNoiseSigma takes the largest
// of; depth also weighs its colour channels by them).
std::vector<double> EstimateNoiseSigmaPerChannel(const cv::Mat& image);

// EstimateChannelNoiseSigma read from the lower quartile of the same |response| instead of its median (scaled so
// that white noise reads its standard deviation), or the median's figure where that is lower; the largest over the
// channels. Texture and edges raise the median once they cover half the pixels, the lower quartile only once they
// cover three quarters: the simulator's noise-free layers scene (a sharp 8 px checker behind thin structures) reads
// 0.015 by the median and 0 here, while noisy views read about the same by both (HCI antinous 0.0019 by the median,
// 0.0021 by the quartile; LFToolbox's decode of the Illum Field scene 0.034 / 0.033 in blue).
double EstimateChannelNoiseSigmaLowerQuartile(const cv::Mat& rgb);

// A texture-robust noise estimate of an RGB or grey image (grey version): the same 3x3 mask, its median absolute
// response per 16x16 block, and the 10th percentile of those block medians (the flattest blocks), scaled so that
// white noise reads its standard deviation (a block median of 256 samples spreads by about 7 %, which puts the 10th
// percentile at 0.906 of the mean). Where texture covers the whole view the plain median reads it as noise: the
// bundled 80x60 mini-Illum decode reads 0.033 per channel by EstimateChannelNoiseSigma and 0.0094 here.
double EstimateNoiseFloor(const cv::Mat& image);

// Below this estimated noise a view counts as clean: a rendered or well-exposed view reads 0.002-0.003.
constexpr double kCleanNoiseLevel = 0.004;

// How much to smooth (Gaussian sigma, pixels) against a noise level: none up to kCleanNoiseLevel, then
// `pixels_per_noise` pixels per unit of noise above it, at most `max_pixels`. Each stage picks its own slope.
double SmoothingForNoise(double noise_sigma, double pixels_per_noise, double max_pixels);

}  // namespace lfsp
