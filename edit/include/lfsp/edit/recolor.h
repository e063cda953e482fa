#pragma once

// Recolouring through light-field superpixels: a selection made once (label ids) changes the same scene surface in
// every view at once. Rays outside the selection and its feather band are left bit-identical.

#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/edit/colour_adjust.h"

namespace lfsp::edit {

struct RecolorOptions {
  ColourAdjustment adjustment;
  // Width in pixels of a soft transition, in each view, from the selected superpixels into their neighbours: a ray
  // outside the selection at distance r (pixels, Euclidean, within its view) from the nearest selected ray gets the
  // edit with strength 1 - r / (feather + 1) when r <= feather. 0 = hard edges.
  float feather_px = 0.0f;
  // In the feather band, multiply the strength by the ray's weight (confidence/vignetting) when the light field has
  // weights, so unreliable rays beside the selection take less of the edit. Selected rays always get all of it.
  bool use_ray_weights = true;
};

struct RecolorStats {
  std::size_t selected_rays = 0;                    // rays whose label is selected (edit strength 1)
  std::size_t feather_rays = 0;                     // rays outside the selection with a strength in (0, 1)
  std::size_t changed_rays = 0;                     // rays whose colour actually changed
  std::vector<std::size_t> selected_rays_per_view;  // row-major, cam = v * nu + u
};

// The edit strength of every ray of one view, CV_32FC1 in [0, 1]: 1 on selected labels, the feather ramp beside
// them, 0 elsewhere. `weights` is the view's ray weights (CV_32FC1) or empty.
cv::Mat EditStrength(const cv::Mat& view_labels, const std::vector<std::int32_t>& selection, float feather_px,
                     const cv::Mat& weights = cv::Mat());

// Recolours `light_field` (RGB, 3 channels) in place. `labels` must have its number of views and view size.
// `selection` is a list of label ids (see selection.h). Throws lfsp::Error on a shape mismatch or bad options.
RecolorStats Recolor(LightField& light_field, const Labels& labels, const std::vector<std::int32_t>& selection,
                     const RecolorOptions& options);

}  // namespace lfsp::edit
