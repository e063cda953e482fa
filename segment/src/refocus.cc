#include "lfsp/segment/refocus.h"

#include <opencv2/imgproc.hpp>

namespace lfsp::segment {

LightField RefocusLightField(const LightField& light_field, double level) {
  const LightFieldShape& shape = light_field.shape();
  LightField out(shape);
  out.transfer = light_field.transfer;
  out.metadata = light_field.metadata;
  const ViewIndex centre = shape.Centre();
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const cv::Matx23d shift(1, 0, (view.u - centre.u) * level, 0, 1, (view.v - centre.v) * level);
    cv::Mat target = out.View(view);
    cv::warpAffine(light_field.View(view), target, shift, target.size(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                   cv::BORDER_REPLICATE);
  }
  return out;
}

DisparityMap RefocusDisparity(const DisparityMap& disparity, double level) {
  DisparityMap out(disparity.width(), disparity.height());
  const std::size_t count = static_cast<std::size_t>(disparity.width()) * static_cast<std::size_t>(disparity.height());
  for (std::size_t i = 0; i < count; ++i) out.data()[i] = disparity.data()[i] + static_cast<float>(level);
  return out;
}

std::vector<double> DefaultRefocusLevels() { return {-1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5}; }

}  // namespace lfsp::segment
