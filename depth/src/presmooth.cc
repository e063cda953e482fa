#include "lfsp/depth/presmooth.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace lfsp::depth {

double PresmoothSigmaForNoise(double noise_sigma) {
  if (!(noise_sigma > kNoiseFloor)) return 0.0;
  return std::min(2.5, 100.0 * (noise_sigma - kNoiseFloor));
}

LightField Presmoothed(const LightField& light_field, double sigma) {
  LightField out = light_field;
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
