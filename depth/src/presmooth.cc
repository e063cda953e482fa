#include "lfsp/depth/presmooth.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace lfsp::depth {

bool NoisyViews(const LightField& light_field, double noise_sigma) {
  return DecodedFromSensor(light_field) || noise_sigma > kDepthCleanNoise;
}

double AutomaticPresmoothSigma(const LightField& light_field, double noise_sigma) {
  return NoisyViews(light_field, noise_sigma) ? kNoisyViewsPresmooth : 0.0;
}

int ExcludedRingFor(const LightField& light_field) {
  if (!DecodedFromSensor(light_field)) return 0;
  const int views = std::min(light_field.shape().nu, light_field.shape().nv);
  return views >= 7 ? 2 : views >= 5 ? 1 : 0;
}

Sampler AutomaticSampler(const LightField& light_field, double noise_sigma) {
  return NoisyViews(light_field, noise_sigma) ? Sampler::kNoiseMatched : Sampler::kBilinear;
}

void PresmoothView(const cv::Mat& view, double sigma, cv::Mat& out) {
  cv::GaussianBlur(view, out, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT);
}

}  // namespace lfsp::depth
