#pragma once

#include <array>
#include <opencv2/core/mat.hpp>

namespace lfsp::decode {

// Sensor-clipped highlights made neutral, as dcraw's "clip" highlight mode does. A channel is clipped at a pixel when
// it reaches `clipped_fraction` of its ceiling: the value a clipped sample decodes to there (`ceilings`, CV_32FC3:
// the inverse white image demosaiced like the capture). Where any channel is clipped, every channel is limited, in
// white-balanced units (times `gains`), to the lowest clipped channel's ceiling.
//
// Why: a highlight clipped in all three channels has lost its colour, and the white balance then paints it in the
// colour of the gains. On a real F01 frame (IMG_1, auto gains 1.01, 1, 1.28) the brightest white petals read blue,
// 1.21 x red, while the unclipped ones read neutral.
//
// Returns the number of pixels changed. `rgb` is the demosaiced camera-space image (CV_32FC3, R first).
long NeutraliseClippedHighlights(cv::Mat& rgb, const cv::Mat& ceilings, const std::array<double, 3>& gains,
                                 float clipped_fraction);

}  // namespace lfsp::decode
