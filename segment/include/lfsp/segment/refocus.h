#pragma once

#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::segment {

// Refocusing as a shear of the light field (Section V-A.5): every view (u, v) is translated so that a centre-view
// disparity d becomes d + level, i.e. view(x, y) <- view(x + (u-uc) level, y + (v-vc) level), bilinear, borders
// replicated. The content of each view is unchanged; only where the views agree moves.
LightField RefocusLightField(const LightField& light_field, double level);

// The matching centre-view disparity: d + level.
DisparityMap RefocusDisparity(const DisparityMap& disparity, double level);

// The paper's refocus levels: -1.5, -1, ..., 1.5.
std::vector<double> DefaultRefocusLevels();

}  // namespace lfsp::segment
