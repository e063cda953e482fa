#pragma once

#include <array>
#include <opencv2/core/mat.hpp>

#include "lfsp/decode/lytro_metadata.h"

namespace lfsp::decode {

// Sensor-clipped highlights made neutral, as dcraw's "clip" highlight mode does. A channel is clipped at a pixel when
// it reaches `clipped_fraction` of its ceiling: the value a clipped sample decodes to there, the inverse white image
// (`inverse_white`, per Bayer pixel, `pattern`) averaged over that channel's sites in the pixel's 3 x 3 neighbourhood
// (what bilinear demosaicking of a sensor clipped everywhere would give). Where any channel is clipped, every channel
// is limited, in white-balanced units (times `gains`), to the lowest clipped channel's ceiling.
//
// Why: a highlight clipped in all three channels has lost its colour, and the white balance then paints it in the
// colour of the gains. On a real F01 frame (IMG_1, auto gains 1.01, 1, 1.28) the brightest white petals read blue,
// 1.21 x red, while the unclipped ones read neutral.
//
// The ceilings are computed pixel by pixel rather than demosaicked into an image: no sensor-size buffer (an Illum's
// would be 0.5 GB). Returns the number of pixels changed. `rgb` is the demosaiced camera-space image (CV_32FC3,
// R first, the sensor's size).
long NeutraliseClippedHighlights(cv::Mat& rgb, const cv::Mat& inverse_white, BayerPattern pattern,
                                 const std::array<double, 3>& gains, float clipped_fraction);

}  // namespace lfsp::decode
