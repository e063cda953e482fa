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
// With `disparity`, the pixel must also lie on the surface at disparity `surface` (within kSameSurfaceTolerance).
bool AroundSource(const std::int32_t* centre, int width, int height, double px, double py, std::int32_t label,
                  const float* disparity = nullptr, double surface = 0.0) {
  if (!(px > -1.0 && py > -1.0 && px < width && py < height)) return false;  // before any cast (NaN, 1e30)
  const int x0 = static_cast<int>(std::floor(px)), y0 = static_cast<int>(std::floor(py));
  const int x1 = static_cast<int>(std::ceil(px)), y1 = static_cast<int>(std::ceil(py));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      if (x < 0 || y < 0 || x >= width || y >= height || centre[y * width + x] != label) continue;
      if (disparity == nullptr || std::abs(disparity[y * width + x] - surface) <= kSameSurfaceTolerance) return true;
    }
  }
  return false;
}

// One side view at offset (du, dv) from the centre: its refined labels in, the carried labels where they hold out.
void CarryIntoView(const std::int32_t* centre, const float* disparity, const std::vector<Plane>& planes, int width,
                   int height, int du, int dv, std::int32_t* labels) {
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
      if (AroundSource(centre, width, height, px, py, labels[i])) continue;
      // Or the refined label's own surface, in front of the carried one, images the centre a rounding away from
      // that label: the centre's pixel grid places an occluder's edge only to within a pixel, and the edge moves
      // by a fraction of a pixel per view step.
      const double own = planes[static_cast<std::size_t>(labels[i])].AtRay(x, y, du, dv);
      if (own > depth[i] && AroundSource(centre, width, height, x + du * own, y + dv * own, labels[i], disparity, own))
        continue;
      labels[i] = carried_label;
    }
  }
}

}  // namespace

void CarryCentreToSideViews(const cv::Mat& centre_disparity, const std::vector<Plane>& planes, Labels& labels) {
  const LightFieldShape& shape = labels.shape();
  const ViewIndex centre = shape.Centre();
  const std::int32_t* centre_labels = labels.ViewData(centre);
  const float* disparity = centre_disparity.ptr<float>(0);
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (view == centre) continue;
    CarryIntoView(centre_labels, disparity, planes, shape.width, shape.height, view.u - centre.u, view.v - centre.v,
                  labels.ViewData(view));
  }
}

}  // namespace lfsp::segment
