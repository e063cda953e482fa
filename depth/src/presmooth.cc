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

LightField Presmoothed(const LightField& light_field, double sigma) {
  // Written view by view straight from the input: no copy of the samples first (the cost volume reads no weights).
  LightField out(light_field.shape());
  out.transfer = light_field.transfer;
  out.metadata = light_field.metadata;
  const LightFieldShape& shape = out.shape();
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    cv::Mat view = out.View(ViewFromCameraNumber(cam, shape.nu));
    cv::GaussianBlur(light_field.View(ViewFromCameraNumber(cam, shape.nu)), view, cv::Size(0, 0), sigma, sigma,
                     cv::BORDER_REFLECT);
  }
  return out;
}

}  // namespace lfsp::depth
