#pragma once

#include <filesystem>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::simulate {

// The HCI benchmark's three evaluation regions (Honauer et al., ACCV 2016) of a rendered scene, known from its
// geometry rather than guessed from the ground-truth disparity: CV_8U maps of the centre view, 255 = in the region.
struct SceneEvaluationMasks {
  cv::Mat discontinuities;  // within `radius` px of a pixel whose 4-neighbour shows another object > `jump` away
  cv::Mat planes;           // planar objects (planes, boards, the empty background), away from discontinuities
  cv::Mat smooth_surfaces;  // curved objects (ellipsoids), away from discontinuities
};

// The file names `lfsp evaluate depth` reads from a scene folder (the benchmark's own names).
inline const std::vector<const char*> kEvaluationMaskFiles = {"mask_discontinuities.png", "mask_planes.png",
                                                              "mask_smooth_surfaces.png"};

// The regions of `rendered` (which must hold centre_objects). `jump` (px per view step) and `radius` (px) default
// to depth::MetricOptions' discontinuity_jump and discontinuity_radius, so that a file and a derived region agree
// wherever the geometry does not say more: a steep but continuous surface is not a discontinuity here, and a
// curved surface is never called a plane.
SceneEvaluationMasks EvaluationMasksOf(const RenderedLightField& rendered, const Scene& scene, double jump = 0.1,
                                       double radius = 5.0);

// Writes the three maps into `folder` under kEvaluationMaskFiles' names (8-bit PNG, 255 inside).
void WriteEvaluationMasks(const SceneEvaluationMasks& masks, const std::filesystem::path& folder);

}  // namespace lfsp::simulate
