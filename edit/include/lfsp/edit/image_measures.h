#pragma once

#include <opencv2/core/mat.hpp>

namespace lfsp::edit {

// Sharpness: the mean squared gradient (forward differences, averaged over channels) of a float image, over the
// pixels where `mask` (CV_8UC1, optional) is non-zero. Defocus blur lowers it.
double GradientEnergy(const cv::Mat& image, const cv::Mat& mask = cv::Mat());

// Peak signal-to-noise ratio in dB of `test` against `reference` (same size and type, float, peak value 1), over the
// pixels where `mask` (CV_8UC1, optional) is non-zero. Identical images give +infinity.
double Psnr(const cv::Mat& reference, const cv::Mat& test, const cv::Mat& mask = cv::Mat());

}  // namespace lfsp::edit
