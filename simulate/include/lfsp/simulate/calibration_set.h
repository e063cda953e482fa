#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "lfsp/simulate/lenslet_camera.h"
#include "lfsp/simulate/raw_capture.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::simulate {

// The rig used for calibration captures: f = 1.2 x width, d = 0.6 (1/Z - 1/0.5 m).
PinholeRig CalibrationRig();

// `count` deterministic checkerboard poses (8 x 6 squares of 25 mm), tilted up to ~20 degrees about varying axes,
// 0.38 .. 0.65 m away, roughly centred.
std::vector<Board> CalibrationBoards(int count);

// A board in front of a plain grey background, seen through `rig`.
Scene CalibrationScene(const Board& board, const PinholeRig& rig);

// Ground truth for calibrating from a light field rendered at width x height: the pinhole-grid intrinsics in that
// pixel frame (f, cx, cy, fB, focus distance, baseline per view step), the pose, and every inner corner's board,
// camera and centre-view coordinates and disparity (in view (u, v) a corner is at (x - (u-uc) d, y - (v-vc) d)).
nlohmann::json CalibrationGroundTruth(const Scene& scene, int width, int height);

}  // namespace lfsp::simulate
