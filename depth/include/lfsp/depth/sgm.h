#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

// Semi-global aggregation (Hirschmueller 2008) over 8 scanline directions. A step of one label between
// neighbours costs p1, a larger jump p2. p2 is lowered across colour edges of the centre view,
// p2 / (1 + |I(p) - I(p - r)| / edge_sigma) (mean absolute RGB difference), never below p1, so depth may jump where
// the image does (occlusion boundaries) while faint, texture-poor surfaces are pulled to smooth depth.
struct SgmOptions {
  float p1 = 0.1f;  // in units of the cost (a per-view mean, see CostOptions)
  float p2 = 1.0f;
  float edge_sigma = 0.02f;
};

// Returns the sum over the directions of the path costs, the same shape as `cost`. `guide` is the CV_32FC3 centre
// view of the cost volume's size.
CostVolume AggregateSemiGlobal(const CostVolume& cost, const cv::Mat& guide, const SgmOptions& options);

}  // namespace lfsp::depth
