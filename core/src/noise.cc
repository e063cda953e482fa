#include "lfsp/core/noise.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace lfsp {

double EstimateNoiseSigma(const cv::Mat& image) {
  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image, grey, cv::COLOR_RGB2GRAY);
  } else {
    grey = image;
  }
  grey.convertTo(grey, CV_32F);
  if (grey.rows < 3 || grey.cols < 3) return 0.0;
  // The mask is the difference of two Laplacians; it is zero on any linear ramp and has sum of squares 36.
  const cv::Mat mask = (cv::Mat_<float>(3, 3) << 1, -2, 1, -2, 4, -2, 1, -2, 1);
  cv::Mat response;
  cv::filter2D(grey, response, CV_32F, mask, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
  // The median of |response| rather than Immerkaer's mean: texture and edges give a minority of large responses,
  // which the mean counts as noise. For Gaussian noise, median |N(0, 36 sigma^2)| = 0.6745 * 6 sigma.
  cv::Mat inner = cv::abs(response(cv::Rect(1, 1, grey.cols - 2, grey.rows - 2)));
  inner = inner.clone();
  std::vector<float> values(inner.begin<float>(), inner.end<float>());
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return static_cast<double>(*middle) / (0.6745 * 6.0);
}

double EstimateChannelNoiseSigma(const cv::Mat& rgb) {
  if (rgb.channels() == 1) return EstimateNoiseSigma(rgb);
  std::vector<cv::Mat> channels;
  cv::split(rgb, channels);
  double largest = 0.0;
  for (const cv::Mat& channel : channels) largest = std::max(largest, EstimateNoiseSigma(channel));
  return largest;
}

double SmoothingForNoise(double noise_sigma, double pixels_per_noise, double max_pixels) {
  if (!(noise_sigma > kCleanNoiseLevel)) return 0.0;
  return std::min(max_pixels, pixels_per_noise * (noise_sigma - kCleanNoiseLevel));
}

}  // namespace lfsp
