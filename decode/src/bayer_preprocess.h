#pragma once

#include <array>
#include <opencv2/core/mat.hpp>
#include <string>

#include "bayer_levels.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode {

// Raw values to a float Bayer image: (value - black) / (white - black) per phase, negatives kept at 0.
cv::Mat ApplyLevels(const RawImage& raw, const PhaseLevels& levels);

// Replaces each pixel that is brighter than all 8 nearest same-colour neighbours (2 px away) by more than `margin`
// with the mean of its 4 axial same-colour neighbours. Micro-images are smooth at the pixel scale (each pixel is a
// different view of the same scene point), so only defects stand out like that. Returns the number replaced.
long CorrectHotPixels(cv::Mat& bayer, float margin);

// The 99.9th percentile of a float image's values (the micro-image centres of a white image), by histogram.
double Percentile999(const cv::Mat& image, float top);

// Divides the Bayer image by the white image, levelled and multiplied per phase by `white_gain`, normalised so
// that its 99.9th percentile is 1; white values below `min_white` are raised to it (gaps between micro-images).
void Devignette(cv::Mat& bayer, const RawImage& white, const PhaseLevels& white_levels,
                const std::array<float, 4>& white_gain, float min_white, const std::string& source);

}  // namespace lfsp::decode
