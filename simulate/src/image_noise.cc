#include "lfsp/simulate/image_noise.h"

#include <opencv2/core.hpp>

namespace lfsp::simulate {

void AddGaussianNoise(LightField& light_field, double sigma, std::uint64_t seed) {
  if (sigma <= 0.0 || light_field.empty()) return;
  cv::Mat all(1, static_cast<int>(light_field.size()), CV_32FC1, light_field.data());
  cv::Mat noise(all.size(), CV_32FC1);
  cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  all += noise;
  cv::min(cv::max(all, 0.0), 1.0, all);
}

}  // namespace lfsp::simulate
