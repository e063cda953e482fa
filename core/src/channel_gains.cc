#include "lfsp/core/channel_gains.h"

#include "lfsp/core/error.h"

namespace lfsp {

std::array<double, 3> FitChannelGains(const cv::Mat& decoded, Transfer decoded_transfer, const cv::Mat& truth,
                                      Transfer truth_transfer) {
  if (decoded.type() != CV_32FC3 || truth.type() != CV_32FC3 || decoded.size() != truth.size())
    throw Error("channel gains: the decoded view and the truth must be RGB float images of the same size");
  std::array<double, 3> cross{}, square{};
  for (int y = 0; y < decoded.rows; ++y) {
    const float* d = decoded.ptr<float>(y);
    const float* t = truth.ptr<float>(y);
    for (int i = 0; i < 3 * decoded.cols; ++i) {
      const double x = LinearSample(d[i], decoded_transfer);
      cross[static_cast<std::size_t>(i % 3)] += x * LinearSample(t[i], truth_transfer);
      square[static_cast<std::size_t>(i % 3)] += x * x;
    }
  }
  std::array<double, 3> gains{1.0, 1.0, 1.0};
  for (std::size_t c = 0; c < 3; ++c)
    if (square[c] > 0.0) gains[c] = cross[c] / square[c];
  return gains;
}

}  // namespace lfsp
