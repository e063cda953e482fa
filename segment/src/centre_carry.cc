#include "centre_carry.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "warp.h"

namespace lfsp::segment {
namespace {

// Is `label` one of the centre labels at the pixels around (px, py), the fractional centre position the ray images
// (floor and ceiling on each axis: one pixel where the position is whole)? Then the carried label differs from it
// only by where the rounding fell.
bool AroundSource(const std::int32_t* centre, int width, int height, double px, double py, std::int32_t label) {
  const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
  const int x1 = static_cast<int>(std::ceil(px)), y1 = static_cast<int>(std::ceil(py));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (x >= 0 && y >= 0 && x < width && y < height && centre[y * width + x] == label) return true;
    }
  }
  return false;
}

// One side view at offset (du, dv) from the centre: its refined labels in, the carried labels where they hold out.
void CarryIntoView(const std::int32_t* centre, const float* disparity, int width, int height, int du, int dv,
                   std::int32_t* labels) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::int32_t> carried(pixels);
  std::vector<float> depth(pixels);
  ForwardWarp(centre, disparity, width, height, du, dv, carried.data(), depth.data());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      const std::int32_t carried_label = carried[i];
      if (carried_label < 0 || carried_label == labels[i]) continue;  // hidden from the centre, or already agreeing
      // The ray images the centre at (x + du d, y + dv d): ForwardWarp's convention read backwards.
      const double px = x + du * static_cast<double>(depth[i]);
      const double py = y + dv * static_cast<double>(depth[i]);
      if (!AroundSource(centre, width, height, px, py, labels[i])) labels[i] = carried_label;
    }
  }
}

}  // namespace

void CarryCentreToSideViews(const cv::Mat& centre_disparity, Labels& labels) {
  const LightFieldShape& shape = labels.shape();
  const ViewIndex centre = shape.Centre();
  const std::int32_t* centre_labels = labels.ViewData(centre);
  const float* disparity = centre_disparity.ptr<float>(0);
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (view == centre) continue;
    CarryIntoView(centre_labels, disparity, shape.width, shape.height, view.u - centre.u, view.v - centre.v,
                  labels.ViewData(view));
  }
}

}  // namespace lfsp::segment
