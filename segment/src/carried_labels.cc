// CarryCentreLabels: the reference segmentation that self-similarity is compared with (see metrics.h).

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/rounding.h"
#include "lfsp/segment/metrics.h"
#include "warp.h"

namespace lfsp::segment {

Labels CarryCentreLabels(const Labels& labels, const DisparityMap& centre_disparity,
                         const std::vector<DisparityMap>& view_disparity) {
  const LightFieldShape& shape = labels.shape();
  if (view_disparity.size() != shape.Views()) throw Error("carry centre labels: need one disparity map per view");
  if (centre_disparity.width() != shape.width || centre_disparity.height() != shape.height) {
    throw Error("carry centre labels: the disparity map does not match the views");
  }
  const ViewIndex c = shape.Centre();
  const std::int32_t* centre = labels.ViewData(c);
  const int w = shape.width, h = shape.height;
  float max_abs = 0.0f;
  for (int i = 0; i < w * h; ++i)
    if (std::isfinite(centre_disparity.data()[i])) max_abs = std::max(max_abs, std::abs(centre_disparity.data()[i]));
  Labels carried(shape);
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    std::int32_t* out = carried.ViewData(view);
    const DisparityMap& d = view_disparity[static_cast<std::size_t>(cam)];
    const int du = view.u - c.u, dv = view.v - c.v;
    std::vector<float> depth(shape.ViewPixels());
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const int i = y * w + x;
        const float disparity = d.at(y, x);
        depth[static_cast<std::size_t>(i)] = disparity;
        out[i] = Labels::kUnlabelled;
        if (!std::isfinite(disparity)) continue;
        const int x0 = RoundHalfAway(x + du * disparity);
        const int y0 = RoundHalfAway(y + dv * disparity);
        if (x0 < 0 || y0 < 0 || x0 >= w || y0 >= h) continue;
        if (std::abs(centre_disparity.at(y0, x0) - disparity) > kSameSurfaceTolerance) continue;  // hidden from c
        out[i] = centre[y0 * w + x0];
      }
    }
    if (view == c) continue;
    FillHoles(out, depth.data(), w, h, du, dv, FillReach(max_abs, du, dv));
  }
  return carried;
}

}  // namespace lfsp::segment
