#include "lfsp/depth/detail_weight.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfsp/core/noise.h"
#include "lfsp/core/registration.h"

namespace lfsp::depth {
namespace {

// The high-pass of DetailHighPass on a single-channel image.
cv::Mat HighPass(const cv::Mat& grey, double sigma) {
  cv::Mat low;
  cv::GaussianBlur(grey, low, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
  return grey - low;
}

// Norm of the kernel that takes white noise into the detail band: Gaussian presmoothing, then the high-pass.
double BandKernelNorm(double presmooth_sigma, double detail_sigma) {
  const int half = static_cast<int>(std::ceil(4.0 * (presmooth_sigma + detail_sigma))) + 2;
  cv::Mat impulse = cv::Mat::zeros(2 * half + 1, 2 * half + 1, CV_32F);
  impulse.at<float>(half, half) = 1.0f;
  if (presmooth_sigma > 0.0)
    cv::GaussianBlur(impulse, impulse, cv::Size(), presmooth_sigma, presmooth_sigma, cv::BORDER_CONSTANT);
  return cv::norm(HighPass(impulse, detail_sigma));
}

double MedianLocalRms(const cv::Mat& detail, double window_sigma) {
  cv::Mat energy;
  cv::multiply(detail, detail, energy);
  cv::GaussianBlur(energy, energy, cv::Size(), window_sigma, window_sigma, cv::BORDER_REFLECT);
  std::vector<float> values(energy.begin<float>(), energy.end<float>());
  auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return std::sqrt(std::max(0.0f, *middle));
}

}  // namespace

cv::Mat DetailHighPass(const cv::Mat& rgb, double sigma) { return HighPass(GreyOf(rgb), sigma); }

double FineBandSignalToNoise(const cv::Mat& raw_centre, const CostOptions& options) {
  if (!(options.detail_sigma > 0.0f)) return 0.0;
  const double noise_in_band = EstimateNoiseFloor(raw_centre) * BandKernelNorm(0.0, options.detail_sigma);
  const double window = options.detail_normalise_sigma > 0.0f ? options.detail_normalise_sigma : 4.0;
  const double signal = MedianLocalRms(DetailHighPass(raw_centre, options.detail_sigma), window);
  return noise_in_band > 0.0 ? signal / noise_in_band : 1e9;
}

std::array<float, 3> ChannelWeightsForNoise(const std::vector<double>& sigma) {
  if (sigma.size() != 3) return {1.0f, 1.0f, 1.0f};
  if (!(*std::max_element(sigma.begin(), sigma.end()) > kCleanNoiseLevel) ||
      !(*std::min_element(sigma.begin(), sigma.end()) > 0.0))
    return {1.0f, 1.0f, 1.0f};
  // Inverse variance: the weighting that combines independent noisy measurements best.
  std::array<double, 3> inverse{};
  for (int c = 0; c < 3; ++c) inverse[c] = 1.0 / (sigma[c] * sigma[c]);
  const double inverse_sum = inverse[0] + inverse[1] + inverse[2];
  std::array<float, 3> weights{};
  for (int c = 0; c < 3; ++c) weights[c] = static_cast<float>(3.0 * inverse[c] / inverse_sum);
  return weights;
}

double FineTextureShare(double fine_band_snr) {
  return std::clamp((fine_band_snr - kFineTextureLow) / (kFineTextureHigh - kFineTextureLow), 0.0, 1.0);
}

float DetailWeightFor(const cv::Mat& raw_centre, const cv::Mat& smoothed_centre, double presmooth_sigma,
                      bool decoded_from_sensor, double fine_band_snr, const CostOptions& options) {
  // Unsmoothed views are clean ones (AutomaticPresmoothSigma), and a rendered light field's noise is white: their
  // detail term stays whole.
  if (!(options.detail_sigma > 0.0f) || !(presmooth_sigma > 0.0) || !decoded_from_sensor) return 1.0f;
  const double share = FineTextureShare(fine_band_snr);
  if (share <= 0.0) return 0.0f;
  const double noise_in_band = EstimateNoiseFloor(raw_centre) * BandKernelNorm(presmooth_sigma, options.detail_sigma);
  const double window = options.detail_normalise_sigma > 0.0f ? options.detail_normalise_sigma : 4.0;
  const double signal = MedianLocalRms(DetailHighPass(smoothed_centre, options.detail_sigma), window);
  const double margin = kDetailNoiseMargin * noise_in_band;
  if (!(signal * signal + margin * margin > 0.0)) return static_cast<float>(share);
  return static_cast<float>(share * signal * signal / (signal * signal + margin * margin));
}

}  // namespace lfsp::depth
