#pragma once

// Starting values for the calibration, from per-view homographies (as in LFToolbox's LFCalInit, reworked):
//  1. the homography board -> centred pixels of each capture's reference view (the view nearest the centre);
//  2. the focal length in pixels, with the principal point at the view centre (recentring puts it there for the
//     centre view), in closed form from the orthogonality constraints of all those homographies;
//  3. each capture's pose from its homography;
//  4. the slopes H31, H33, H13 (and H42, H44, H24) by linear least squares over every observation: with
//     H11 = 0, a board point P (camera frame) seen at centred index (i, k) satisfies P_x = H13 k + (H31 i + H33 k) P_z.

#include <array>
#include <string>
#include <vector>

#include "lfsp/calibrate/corners.h"
#include "lfsp/calibrate/ray_model.h"
#include "ray_distance_cost.h"

namespace lfsp::calibrate::internal {

using Pose = std::array<double, 6>;  // angle-axis, translation (board -> camera)

struct InitialEstimate {
  Slopes slopes{};
  std::vector<Pose> poses;  // one per capture
};

InitialEstimate InitialiseFromHomographies(const std::vector<CaptureCorners>& captures,
                                           const std::vector<Observation>& observations, double square_size);

}  // namespace lfsp::calibrate::internal
