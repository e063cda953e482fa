#pragma once

#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/light_field.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::simulate {

struct RenderOptions {
  int nu = 9;       // views per row
  int nv = 9;       // views per column
  int width = 128;  // pixels per view
  int height = 128;
  int supersampling = 3;         // samples per pixel along each axis (3 -> 9 stratified samples); 1 = no anti-aliasing
  float disparity_scale = 1.0f;  // multiplies every scene disparity (scene disparities are pixels per view step)
  Transfer transfer = Transfer::kSrgb;  // kSrgb: texture colours as given; kLinear: decoded to linear radiance
  bool per_view_disparity = true;       // fill RenderedLightField::view_disparity
};

// An ideal light field with ground truth known by construction.
struct RenderedLightField {
  LightField light_field;                    // nv x nu views, RGB in [0, 1]
  Labels labels;                             // object label of the ray through each pixel centre (nearest wins)
  std::vector<DisparityMap> view_disparity;  // per view (row-major cam = v * nu + u), of the pixel-centre ray
  DisparityMap disparity;                    // centre view (same as view_disparity[centre])
  cv::Mat centre_objects;                    // CV_32S, centre view: index into Scene::objects of each pixel-centre
                                             // ray's hit, -1 where it hits nothing (the evaluation masks use it)
};

// Throws lfsp::Error unless the options can be rendered (views 1..64 per axis, view size 1..16384, supersampling
// 1..16, a finite disparity scale). RenderLightField checks them; callers that write files check first.
void CheckRenderOptions(const RenderOptions& options);

// Renders every view by tracing, for each (anti-aliasing sub-)pixel, the ray of view (u, v) through the scene.
// OpenMP-parallel; deterministic (no randomness).
RenderedLightField RenderLightField(const Scene& scene, const RenderOptions& options);

// The project's bundle (LF + centre disparity + labels) with metadata describing the scene and disparity range.
Bundle ToBundle(const RenderedLightField& rendered, const Scene& scene);

// The nearest surface along a ray, in centre-view pixel coordinates: the ray of view offset (s, t) = (u-uc, v-vc)
// through view pixel (px, py) is the line X = px + s d, Y = py + t d in (X, Y, d) space.
struct RayHit {
  int object = -1;  // index into Scene::objects, -1 = nothing
  float disparity = 0.0f;
  float x = 0.0f;  // centre-view position of the hit, pixels
  float y = 0.0f;
};

}  // namespace lfsp::simulate
