#include "lfsp/depth/presmooth.h"

#include "lfsp/depth/detail_weight.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace lfsp::depth {

double PresmoothSigmaForNoise(double noise_sigma) {
  return std::clamp(1000.0 * (noise_sigma - kDepthCleanNoise), 0.0, 2.5);
}

int ExcludedRingFor(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  return DecodedFromSensor(light_field) && std::min(shape.nu, shape.nv) >= 5 ? 1 : 0;
}

double PresmoothFloorFor(const LightField& light_field) {
  return DecodedFromSensor(light_field) ? kLensletPresmoothFloor : 0.0;
}

double AutomaticPresmoothSigma(const LightField& light_field, double noise_sigma, double fine_band_snr) {
  const double floor = PresmoothFloorFor(light_field);
  if (floor > 0.0 && fine_band_snr >= kFineTextureHigh) return floor;
  return std::max(PresmoothSigmaForNoise(noise_sigma), floor);
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
