#pragma once

// Rectification of a decoded light field (as LFToolbox's LFCalRectifyLF): every output sample n takes the ray of
// an ideal, undistorted intrinsic matrix, H_rect n; that ray is traced back through the calibrated model (inverse
// distortion, then H_cal^-1) to the measured sample index it was recorded at, and the input is interpolated there
// (linear in all four indices). After rectification phi = H_rect n holds exactly (up to interpolation), so straight
// lines stay straight in every view and the views differ only by disparity shifts.

#include "lfsp/calibrate/ray_model.h"
#include "lfsp/core/light_field.h"

namespace lfsp::calibrate {

struct RectifyOptions {
  int inverse_distortion_iterations = 8;  // fixed-point iterations of the inverse distortion (LFToolbox: 2)
};

// The default ideal model for a calibrated one: slopes averaged so pixels are square and the horizontal and
// vertical disparities agree, H11 = H22 = their mean, recentred, no distortion.
RayModel RectifiedModel(const RayModel& calibrated, const LightFieldShape& shape);

// Resamples every view (and the weights, if any). Samples whose source lies outside the input get value 0 and
// weight 0 (weights are created for that if the input has none). Throws lfsp::Error if `input` is empty.
LightField Rectify(const LightField& input, const RayModel& calibrated, const RayModel& rectified,
                   const RectifyOptions& options = {});

}  // namespace lfsp::calibrate
