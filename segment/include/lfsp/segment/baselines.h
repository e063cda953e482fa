#pragma once

#include "lfsp/core/light_field.h"

namespace lfsp::segment {

// The competitors of the paper's Tables and Table III, run on a light field with the same superpixel size.
struct BaselineParams {
  int size = 20;             // region size (grid step), pixels
  float slic_ruler = 10.0f;  // SLIC compactness m (Lab units)
  int slic_iterations = 10;
  float lsc_ratio = 0.075f;  // LSC compactness
  int lsc_iterations = 10;
  double supervoxel_compactness = 10.0;  // SLIC supervoxel compactness m (Lab units)
  int supervoxel_iterations = 5;
  int temporal_step = 0;  // supervoxel grid step along the view sequence; 0 = size
};

// SLIC (OpenCV ximgproc, CIELab, connectivity enforced) on every view independently. Nothing links the views, so a
// label is the index of the seed-grid cell (step `size`) holding the superpixel's centroid, the same grid in every
// view; that is the only way to follow a per-view superpixel across views (self-similarity), and it makes ELR
// meaningless for these methods.
Labels SlicPerView(const LightField& light_field, const BaselineParams& params = {});

// LSC (Li and Chen, OpenCV ximgproc) on every view independently, labels = grid-cell indices as for SlicPerView.
Labels LscPerView(const LightField& light_field, const BaselineParams& params = {});

// How the views are ordered into a video for a supervoxel method (the paper's Table III).
enum class ViewOrder { kRowFirst, kColumnFirst };

// SLIC supervoxels: 3D SLIC (k-means on CIELab + x, y, frame) over the views arranged as a video, row-first
// (frame = v * nu + u) or column-first (frame = u * nv + v), with cubic seeds of `size` pixels and
// `temporal_step` frames.
Labels SlicSupervoxels(const LightField& light_field, ViewOrder order, const BaselineParams& params = {});

}  // namespace lfsp::segment
