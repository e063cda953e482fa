#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/core/uninitialized_vector.h"

namespace lfsp::segment {

// CIELab samples of every ray, layout [v][u][y][x][3] like the light field (L in 0..100, a/b about -100..100).
using LabRays = UninitializedVector<float>;

// The light field's LabRays. Linear light fields are sRGB-encoded first, so distances are perceptual for both
// transfers.
LabRays LabOfLightField(const LightField& light_field);

// Gaussian-smooths every view of such a buffer in place (sigma in pixels), in parallel over views.
void SmoothLabViews(LabRays& lab, const LightFieldShape& shape, double sigma);

// One view of such a buffer as a zero-copy CV_32FC3 matrix.
cv::Mat LabView(LabRays& lab, const LightFieldShape& shape, ViewIndex view);

}  // namespace lfsp::segment
