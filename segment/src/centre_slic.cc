#include "centre_slic.h"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/ximgproc/slic.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "lfsp/core/error.h"

namespace lfsp::segment {

int CompactLabels(cv::Mat& labels) {
  std::unordered_map<int, int> renumber;
  for (int y = 0; y < labels.rows; ++y) {
    int* row = labels.ptr<int>(y);
    for (int x = 0; x < labels.cols; ++x) {
      const auto [it, inserted] = renumber.try_emplace(row[x], static_cast<int>(renumber.size()));
      row[x] = it->second;
    }
  }
  return static_cast<int>(renumber.size());
}

namespace {

// OpenCV's SLIC sums squared feature differences in float and gives a pixel to a seed only when that distance is
// below FLT_MAX. A disparity map of 3e38, scaled, overflows to infinity: every distance is then infinite or NaN, no
// seed claims any pixel, and the "superpixels" are SLIC's initial labels, not a segmentation. Features within
// +-kLargestFeature keep every distance finite (four channels of (2e15)^2 sum to 1.6e31, far below 3.4e38), so larger
// ones are refused as input that cannot be segmented.
constexpr double kLargestFeature = 1e15;

void RequireBounded(const cv::Mat& features, const char* what) {
  const cv::Mat values = features.reshape(1);
  if (cv::checkRange(values, true, nullptr, -kLargestFeature, kLargestFeature)) return;
  double lowest = 0, highest = 0;
  cv::minMaxLoc(values, &lowest, &highest);
  throw Error(std::string("LFSP: the centre view's ") + what + " are too large to segment (scaled to " +
              std::to_string(lowest) + " .. " + std::to_string(highest) + ", beyond +-1e15 or not finite)");
}

}  // namespace

cv::Mat CentreSuperpixels(const cv::Mat& lab, const cv::Mat& disparity, double disparity_range,
                          const LfspParams& params, int& count) {
  // OpenCV's SLIC measures sum over channels of squared differences plus (ruler / size)^2 times the squared image
  // distance. Scaling every term of our energy by colour_scale^2 makes it exactly that: Lab channels as they are,
  // a disparity channel scaled by colour_scale sqrt(lambda_d) / range, and ruler = colour_scale sqrt(lambda_p).
  std::vector<cv::Mat> channels;
  cv::split(lab, channels);
  cv::Mat scaled_disparity;
  disparity.convertTo(scaled_disparity, CV_32F, params.colour_scale * std::sqrt(params.lambda_d) / disparity_range);
  RequireBounded(lab, "colours (Lab)");
  RequireBounded(scaled_disparity, "disparities");
  channels.push_back(scaled_disparity);
  cv::Mat features;
  cv::merge(channels, features);

  const float ruler = static_cast<float>(params.colour_scale * std::sqrt(params.lambda_p));
  cv::Ptr<cv::ximgproc::SuperpixelSLIC> slic =
      cv::ximgproc::createSuperpixelSLIC(features, cv::ximgproc::SLIC, params.size, ruler);
  slic->iterate(params.slic_iterations);
  slic->enforceLabelConnectivity(25);
  cv::Mat labels;
  slic->getLabels(labels);
  count = CompactLabels(labels);
  return labels;
}

}  // namespace lfsp::segment
