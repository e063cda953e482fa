#include "lfsp/segment/baselines.h"

#include <algorithm>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/lsc.hpp>
#include <opencv2/ximgproc/slic.hpp>
#include <vector>

#include "centre_slic.h"
#include "lab_image.h"
#include "lfsp/core/error.h"
#include "lfsp/core/visualize.h"
#include "lfsp/segment/params.h"

namespace lfsp::segment {
namespace {

// Names each superpixel of one view by the seed-grid cell (step `size`) that holds its centroid, so a label means
// "the superpixel at this grid position" in every view: per-view methods have no other link between views, and this
// is how one of their superpixels is followed across views (self-similarity), as the paper does for SLIC and LSC.
// Superpixels whose centroid falls in an already named cell get fresh labels after the grid's, so the partition is
// unchanged.
cv::Mat GridIndexed(const cv::Mat& labels, int size) {
  cv::Mat compact = labels.clone();
  const int count = CompactLabels(compact);
  std::vector<double> sx(static_cast<std::size_t>(count), 0.0), sy(sx), n(sx);
  for (int y = 0; y < compact.rows; ++y) {
    for (int x = 0; x < compact.cols; ++x) {
      const std::size_t k = static_cast<std::size_t>(compact.at<int>(y, x));
      sx[k] += x;
      sy[k] += y;
      n[k] += 1.0;
    }
  }
  const int cells_x = (compact.cols + size - 1) / size, cells_y = (compact.rows + size - 1) / size;
  std::vector<int> name(static_cast<std::size_t>(count));
  std::vector<bool> taken(static_cast<std::size_t>(cells_x * cells_y), false);
  int fresh = cells_x * cells_y;
  for (std::size_t k = 0; k < name.size(); ++k) {
    const int cx = std::min(cells_x - 1, static_cast<int>(sx[k] / n[k]) / size);
    const int cy = std::min(cells_y - 1, static_cast<int>(sy[k] / n[k]) / size);
    const std::size_t cell = static_cast<std::size_t>(cy * cells_x + cx);
    if (taken[cell]) {
      name[k] = fresh++;
    } else {
      taken[cell] = true;
      name[k] = static_cast<int>(cell);
    }
  }
  for (int y = 0; y < compact.rows; ++y) {
    for (int x = 0; x < compact.cols; ++x)
      compact.at<int>(y, x) = name[static_cast<std::size_t>(compact.at<int>(y, x))];
  }
  return compact;
}

// Runs `segment_view(view) -> CV_32SC1 labels` on every view.
template <typename SegmentView>
Labels PerView(const LightField& light_field, SegmentView segment_view) {
  const LightFieldShape& shape = light_field.shape();
  Labels labels(shape);
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    segment_view(view).copyTo(labels.View(view));
  }
  return labels;
}

}  // namespace

Labels SlicPerView(const LightField& light_field, const BaselineParams& params) {
  RequireSuperpixelSizeFits(params.size, light_field.shape(), "per-view SLIC");
  LabRays lab = LabOfLightField(light_field);
  return PerView(light_field, [&](ViewIndex view) {
    cv::Ptr<cv::ximgproc::SuperpixelSLIC> slic = cv::ximgproc::createSuperpixelSLIC(
        LabView(lab, light_field.shape(), view), cv::ximgproc::SLIC, params.size, params.slic_ruler);
    slic->iterate(params.slic_iterations);
    slic->enforceLabelConnectivity(25);
    cv::Mat labels;
    slic->getLabels(labels);
    return GridIndexed(labels, params.size);
  });
}

Labels LscPerView(const LightField& light_field, const BaselineParams& params) {
  RequireSuperpixelSizeFits(params.size, light_field.shape(), "per-view LSC");
  return PerView(light_field, [&](ViewIndex view) {
    cv::Mat rgb8, lab8;
    cv::Mat source = DisplayEncoded(light_field.View(view), light_field.transfer);  // LSC expects sRGB
    if (source.channels() == 1) cv::cvtColor(source, source, cv::COLOR_GRAY2RGB);
    source.convertTo(rgb8, CV_8U, 255.0);
    cv::cvtColor(rgb8, lab8, cv::COLOR_RGB2Lab);
    cv::Ptr<cv::ximgproc::SuperpixelLSC> lsc = cv::ximgproc::createSuperpixelLSC(lab8, params.size, params.lsc_ratio);
    lsc->iterate(params.lsc_iterations);
    lsc->enforceLabelConnectivity(25);
    cv::Mat labels;
    lsc->getLabels(labels);
    return GridIndexed(labels, params.size);
  });
}

}  // namespace lfsp::segment
