#pragma once

// One gain per colour channel that best maps a decoded view onto the truth, in linear light: what a comparison
// with a simulated truth leaves out as exposure and white balance rather than error. The decode's centre-view
// fidelity (decode/view_quality.h) and the pipeline's truth panel (apps/pipeline/truth_comparison.h) both use it.

#include <array>

#include <opencv2/core.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp {

// A sample value encoded by `transfer`, in linear light, in double.
inline double LinearSample(float value, Transfer transfer) {
  return transfer == Transfer::kLinear ? static_cast<double>(value) : SrgbToLinear(static_cast<double>(value));
}

// For each channel c, the g_c minimising sum (g_c * decoded_c - truth_c)^2 over every pixel, both in linear light;
// 1 for a channel that is zero throughout. The images must be CV_32FC3 of the same size (ROIs are fine).
std::array<double, 3> FitChannelGains(const cv::Mat& decoded, Transfer decoded_transfer, const cv::Mat& truth,
                                      Transfer truth_transfer);

}  // namespace lfsp
