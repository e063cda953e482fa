#pragma once

#include <array>
#include <opencv2/core/mat.hpp>
#include <string>

#include "bayer_levels.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode {

// Raw values to a float Bayer image: (value - black) / (white - black) per phase, negatives kept at 0.
cv::Mat ApplyLevels(const RawImage& raw, const PhaseLevels& levels);

// The 99.9th percentile of a float image's values (the micro-image centres of a white image), by histogram.
double Percentile999(const cv::Mat& image, float top);

// 1 / (white image, levelled, multiplied per phase by `white_gain`, normalised so its 99.9th percentile is 1),
// with white values below `min_white` raised to it (gaps between micro-images), so that devignetting is a product.
cv::Mat InverseWhite(const RawImage& white, const PhaseLevels& white_levels, const std::array<float, 4>& white_gain,
                     float min_white, const std::string& source);

// The capture's Bayer image in one pass: levels, hot-pixel correction and devignetting (times `inverse_white`).
// A pixel brighter than all 8 nearest same-colour neighbours (2 px away) by more than `hot_margin` (fraction of
// white - black; <= 0 disables) is replaced by the mean of its 4 axial same-colour neighbours: micro-images are
// smooth at the pixel scale (each pixel is a different view of one scene point), so only defects stand out like
// that. `hot_pixels` receives the number replaced, `clipped_samples` the number levelled at or above
// kClippedLevel (the sensor's or the file's ceiling, before devignetting).
cv::Mat LevelAndDevignette(const RawImage& raw, const PhaseLevels& levels, const cv::Mat& inverse_white,
                           float hot_margin, long& hot_pixels, long& clipped_samples);

// A levelled sample this close to 1 counts as clipped: a 12-bit sensor's last codes, or an 8-bit JPEG mosaic's 255
// after the restoration has moved it by a code or two.
inline constexpr float kClippedLevel = 0.98f;

}  // namespace lfsp::decode
