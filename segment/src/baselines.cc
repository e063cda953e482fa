#include "lfsp/segment/baselines.h"

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/lsc.hpp>
#include <opencv2/ximgproc/slic.hpp>

#include "centre_slic.h"
#include "lab_image.h"
#include "lfsp/core/error.h"

namespace lfsp::segment {
namespace {

void CheckSize(int size) {
  if (size < 2) throw Error("baseline superpixels: size must be at least 2, got " + std::to_string(size));
}

// Runs `segment_view(view) -> CV_32SC1 labels` on every view and offsets each view's labels so they are unique.
template <typename SegmentView>
Labels PerView(const LightField& light_field, SegmentView segment_view) {
  const LightFieldShape& shape = light_field.shape();
  Labels labels(shape);
  const int views = static_cast<int>(shape.Views());
  std::vector<int> counts(static_cast<std::size_t>(views));
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    cv::Mat out = segment_view(view);
    counts[static_cast<std::size_t>(cam)] = CompactLabels(out);
    out.copyTo(labels.View(view));
  }
  int offset = 0;
  for (int cam = 0; cam < views; ++cam) {
    std::int32_t* data = labels.ViewData(ViewFromCameraNumber(cam, shape.nu));
    for (std::size_t i = 0; i < shape.ViewPixels(); ++i) data[i] += offset;
    offset += counts[static_cast<std::size_t>(cam)];
  }
  return labels;
}

}  // namespace

Labels SlicPerView(const LightField& light_field, const BaselineParams& params) {
  CheckSize(params.size);
  std::vector<float> lab = LabOfLightField(light_field);
  return PerView(light_field, [&](ViewIndex view) {
    cv::Ptr<cv::ximgproc::SuperpixelSLIC> slic = cv::ximgproc::createSuperpixelSLIC(
        LabView(lab, light_field.shape(), view), cv::ximgproc::SLIC, params.size, params.slic_ruler);
    slic->iterate(params.slic_iterations);
    slic->enforceLabelConnectivity(25);
    cv::Mat labels;
    slic->getLabels(labels);
    return labels;
  });
}

Labels LscPerView(const LightField& light_field, const BaselineParams& params) {
  CheckSize(params.size);
  return PerView(light_field, [&](ViewIndex view) {
    cv::Mat rgb8, lab8;
    cv::Mat source = light_field.View(view);
    if (source.channels() == 1) cv::cvtColor(source, source, cv::COLOR_GRAY2RGB);
    source.convertTo(rgb8, CV_8U, 255.0);
    cv::cvtColor(rgb8, lab8, cv::COLOR_RGB2Lab);
    cv::Ptr<cv::ximgproc::SuperpixelLSC> lsc = cv::ximgproc::createSuperpixelLSC(lab8, params.size, params.lsc_ratio);
    lsc->iterate(params.lsc_iterations);
    lsc->enforceLabelConnectivity(25);
    cv::Mat labels;
    lsc->getLabels(labels);
    return labels;
  });
}

}  // namespace lfsp::segment
