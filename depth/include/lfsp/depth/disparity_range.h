#pragma once

// The disparity range of a light field that records none (views folders from other tools, decodes of real
// captures), estimated from the views themselves.

#include "lfsp/core/conventions.h"
#include "lfsp/core/light_field.h"

namespace lfsp::depth {

struct RangeEstimate {
  DisparityRange range;     // what depth should sweep: the data's disparities, padded
  DisparityRange measured;  // 2nd and 98th percentiles of the coarse sweep's winners, unpadded
  double searched = 0.0;    // the sweep covered -searched .. +searched px per view step
  int pixels_used = 0;      // textured pixels whose coarse cost had a clear minimum
};

// A coarse plane sweep: the centre view against the four views a third of the way to the angular edge (left,
// right, above, below), on grey images halved in size when wider than 256 px, every 0.05 px per view step over
// +-min(8, a quarter of the view width per view offset), each pixel scored by its two best-matching views (an
// occluded view does not decide). The sweep's winner counts where the centre view is textured and the cost curve has
// a clear minimum (below half its mean); the range is the winners' 2nd..98th percentile padded by 10 % and 0.1 px.
// Throws lfsp::Error when fewer than 1 % of the pixels qualify (a textureless light field has no measurable
// disparity).
RangeEstimate EstimateDisparityRange(const LightField& light_field);

}  // namespace lfsp::depth
