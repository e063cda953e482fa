#include "lfsp/simulate/render.h"

#include <algorithm>
#include <cmath>

#include "lfsp/core/error.h"
#include "ray_tracer.h"

namespace lfsp::simulate {
void CheckRenderOptions(const RenderOptions& o) {
  if (o.nu < 1 || o.nv < 1 || o.nu > 64 || o.nv > 64) throw Error("render: views must be 1..64 per axis");
  if (o.width < 1 || o.height < 1 || o.width > 16384 || o.height > 16384)
    throw Error("render: view size must be 1..16384 pixels per axis");
  if (o.supersampling < 1 || o.supersampling > 16) throw Error("render: supersampling must be 1..16");
  if (!std::isfinite(o.disparity_scale)) throw Error("render: disparity scale must be finite");
}

RenderedLightField RenderLightField(const Scene& scene, const RenderOptions& options) {
  CheckRenderOptions(options);
  if (scene.objects.empty()) throw Error("render: scene '" + scene.name + "' has no objects");
  const LightFieldShape shape{options.nu, options.nv, options.width, options.height, 3};
  const ViewIndex centre = shape.Centre();
  const float max_offset =
      static_cast<float>(std::max({centre.u, options.nu - 1 - centre.u, centre.v, options.nv - 1 - centre.v}));
  const RayTracer tracer(scene, options.width, options.height, options.disparity_scale, max_offset, options.transfer);

  RenderedLightField out;
  out.light_field = LightField(shape);
  out.light_field.transfer = options.transfer;
  out.labels = Labels(shape);
  const bool keep_views = options.per_view_disparity;
  out.view_disparity.assign(keep_views ? shape.Views() : 0, DisparityMap(options.width, options.height));
  out.disparity = DisparityMap(options.width, options.height);
  out.centre_objects = cv::Mat(options.height, options.width, CV_32S, cv::Scalar(-1));

  const int n = options.supersampling;
  const float inv_samples = 1.0f / static_cast<float>(n * n);
  const bool centre_in_grid = (n % 2) == 1;  // odd grids contain the pixel centre as their middle sample
  const int rows = options.nv * options.nu * options.height;
#pragma omp parallel for schedule(dynamic, 4)
  for (int row = 0; row < rows; ++row) {
    const int y = row % options.height;
    const int cam = row / options.height;
    const ViewIndex view = ViewFromCameraNumber(cam, options.nu);
    const float s = static_cast<float>(view.u - centre.u);
    const float t = static_cast<float>(view.v - centre.v);
    float* rgb = out.light_field.ViewData(view) + static_cast<std::size_t>(y) * options.width * 3;
    std::int32_t* labels = out.labels.ViewData(view) + static_cast<std::size_t>(y) * options.width;
    for (int x = 0; x < options.width; ++x) {
      float sum[3] = {0, 0, 0};
      RayHit centre_hit;
      for (int j = 0; j < n; ++j) {
        const float py = static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(n) - 0.5f;
        for (int i = 0; i < n; ++i) {
          const float px = static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(n) - 0.5f;
          const RayHit hit = tracer.Trace(px, py, s, t);
          const Rgb c = tracer.Shade(hit, s, t);
          sum[0] += c[0];
          sum[1] += c[1];
          sum[2] += c[2];
          if (centre_in_grid && i == n / 2 && j == n / 2) centre_hit = hit;
        }
      }
      if (!centre_in_grid) centre_hit = tracer.Trace(static_cast<float>(x), static_cast<float>(y), s, t);
      for (int c = 0; c < 3; ++c) rgb[3 * x + c] = std::clamp(sum[c] * inv_samples, 0.0f, 1.0f);
      labels[x] = tracer.Label(centre_hit.object);
      if (keep_views) out.view_disparity[static_cast<std::size_t>(cam)].at(y, x) = centre_hit.disparity;
      if (view == centre) {
        out.disparity.at(y, x) = centre_hit.disparity;
        out.centre_objects.at<std::int32_t>(y, x) = centre_hit.object;
      }
    }
  }

  const auto range = scene.DisparityRange();
  DisparityRange disparity_range{range[0] * options.disparity_scale, range[1] * options.disparity_scale};
  if (disparity_range.min > disparity_range.max) std::swap(disparity_range.min, disparity_range.max);
  SetDisparityRange(out.light_field.metadata, disparity_range);
  out.light_field.metadata["simulate"] = {{"scene", scene.name},
                                          {"supersampling", options.supersampling},
                                          {"disparity_scale", options.disparity_scale},
                                          {"objects", static_cast<int>(scene.objects.size())},
                                          {"max_label", scene.MaxLabel()}};
  return out;
}

Bundle ToBundle(const RenderedLightField& rendered, const Scene& scene) {
  Bundle bundle;
  bundle.light_field = rendered.light_field;
  bundle.disparity = rendered.disparity;
  bundle.labels = rendered.labels;
  bundle.light_field.metadata["simulate"]["scene_json"] = SceneToJson(scene).dump();
  return bundle;
}

}  // namespace lfsp::simulate
