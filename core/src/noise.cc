#include "lfsp/core/noise.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace lfsp {

namespace {

// For Gaussian noise, median |N(0, 36 sigma^2)| = 0.6745 * 6 sigma (the mask below has sum of squares 36), and its
// lower quartile 0.3186 * 6 sigma.
constexpr double kMedianResponsePerSigma = 0.6745 * 6.0;
constexpr double kLowerQuartileResponsePerSigma = 0.3186 * 6.0;

// |response| of the grey image to the mask that cancels any plane (the difference of two Laplacians), without the
// one-pixel border; empty if the image is smaller than 3x3.
cv::Mat PlaneFreeResponse(const cv::Mat& image) {
  cv::Mat grey;
  if (image.channels() == 3) {
    cv::cvtColor(image, grey, cv::COLOR_RGB2GRAY);
  } else {
    grey = image;
  }
  grey.convertTo(grey, CV_32F);
  if (grey.rows < 3 || grey.cols < 3) return {};
  const cv::Mat mask = (cv::Mat_<float>(3, 3) << 1, -2, 1, -2, 4, -2, 1, -2, 1);
  cv::Mat response;
  cv::filter2D(grey, response, CV_32F, mask, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
  return cv::abs(response(cv::Rect(1, 1, grey.cols - 2, grey.rows - 2)));
}

// The value `fraction` of the way up the sorted values (0.5: the median); reorders them.
float Quantile(std::vector<float>& values, double fraction) {
  auto at = values.begin() + static_cast<std::ptrdiff_t>(static_cast<double>(values.size()) * fraction);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

float Median(std::vector<float>& values) { return Quantile(values, 0.5); }

// The values of PlaneFreeResponse, for their quantiles; empty if the image is smaller than 3x3.
std::vector<float> ResponseValues(const cv::Mat& image) {
  const cv::Mat response = PlaneFreeResponse(image);
  if (response.empty()) return {};
  return std::vector<float>(response.begin<float>(), response.end<float>());
}

// The median's and the lower quartile's estimates of one channel, the smaller of the two.
double LowerQuartileNoiseSigma(const cv::Mat& channel) {
  std::vector<float> values = ResponseValues(channel);
  if (values.empty()) return 0.0;
  const double median = Median(values) / kMedianResponsePerSigma;
  const double lower_quartile = Quantile(values, 0.25) / kLowerQuartileResponsePerSigma;
  return std::min(median, lower_quartile);
}

}  // namespace

double EstimateNoiseSigma(const cv::Mat& image) {
  std::vector<float> values = ResponseValues(image);
  if (values.empty()) return 0.0;
  // The median of |response| rather than Immerkaer's mean: texture and edges give a minority of large responses,
  // which the mean counts as noise.
  return static_cast<double>(Median(values)) / kMedianResponsePerSigma;
}

double EstimateNoiseFloor(const cv::Mat& image) {
  constexpr int kBlock = 16;
  constexpr double kTenthPercentileOfBlockMedians = 0.906;  // for white noise, relative to the median
  const cv::Mat response = PlaneFreeResponse(image);
  if (response.rows < kBlock || response.cols < kBlock) return EstimateNoiseSigma(image);
  std::vector<float> block_medians;
  std::vector<float> values(static_cast<std::size_t>(kBlock * kBlock));
  for (int y = 0; y + kBlock <= response.rows; y += kBlock)
    for (int x = 0; x + kBlock <= response.cols; x += kBlock) {
      const cv::Mat block = response(cv::Rect(x, y, kBlock, kBlock)).clone();
      values.assign(block.begin<float>(), block.end<float>());
      block_medians.push_back(Median(values));
    }
  auto tenth = block_medians.begin() + static_cast<std::ptrdiff_t>(block_medians.size() / 10);
  std::nth_element(block_medians.begin(), tenth, block_medians.end());
  return static_cast<double>(*tenth) / (kMedianResponsePerSigma * kTenthPercentileOfBlockMedians);
}

std::vector<double> EstimateNoiseSigmaPerChannel(const cv::Mat& image) {
  if (image.channels() == 1) return {EstimateNoiseSigma(image)};
  std::vector<cv::Mat> channels;
  cv::split(image, channels);
  std::vector<double> sigmas;
  for (const cv::Mat& channel : channels) sigmas.push_back(EstimateNoiseSigma(channel));
  return sigmas;
}

double EstimateChannelNoiseSigma(const cv::Mat& rgb) {
  const std::vector<double> sigmas = EstimateNoiseSigmaPerChannel(rgb);
  return *std::max_element(sigmas.begin(), sigmas.end());
}

double EstimateChannelNoiseSigmaLowerQuartile(const cv::Mat& rgb) {
  std::vector<cv::Mat> channels;
  cv::split(rgb, channels);
  double largest = 0.0;
  for (const cv::Mat& channel : channels) largest = std::max(largest, LowerQuartileNoiseSigma(channel));
  return largest;
}

double SmoothingForNoise(double noise_sigma, double pixels_per_noise, double max_pixels) {
  if (!(noise_sigma > kCleanNoiseLevel)) return 0.0;
  return std::min(max_pixels, pixels_per_noise * (noise_sigma - kCleanNoiseLevel));
}

}  // namespace lfsp
