#pragma once

#include <array>
#include <opencv2/core/mat.hpp>

#include "lfsp/decode/demosaic.h"
#include "lfsp/decode/lytro_metadata.h"

namespace lfsp::decode {

// Sensor-clipped highlights made neutral, as dcraw's "clip" highlight mode does. A channel is clipped at a pixel when
// it reaches `clipped_fraction` of its ceiling: the value a clipped sample decodes to there, that is the inverse
// white image (`inverse_white`, per Bayer pixel) demosaicked exactly as the capture was (`pattern`, `method`,
// `micro_images`; the micro-images' vignetting makes any other interpolation differ by more than the fraction's
// margin). Where any channel is clipped, every channel is limited, in white-balanced units (times `gains`), to the
// lowest clipped channel's ceiling.
//
// Why: a highlight clipped in all three channels has lost its colour, and the white balance then paints it in the
// colour of the gains. On a real F01 frame (IMG_1, auto gains 1.01, 1, 1.28) the brightest white petals read blue,
// 1.21 x red, while the unclipped ones read neutral.
//
// The ceilings are demosaicked in bands of rows, so no second sensor-size image is held (an Illum's would be
// 0.5 GB). Returns the number of pixels changed. `rgb` is the demosaicked camera-space image (CV_32FC3, R first,
// the sensor's size).
long NeutraliseClippedHighlights(cv::Mat& rgb, const cv::Mat& inverse_white, BayerPattern pattern,
                                 DemosaicMethod method, const MicroImages& micro_images,
                                 const std::array<double, 3>& gains, float clipped_fraction);

}  // namespace lfsp::decode
