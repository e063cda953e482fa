#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

// Semi-global aggregation (Hirschmueller 2008) over 8 scanline directions. A step of one label between
// neighbours costs p1, a larger jump p2. p2 is lowered across colour edges of the centre view,
// p2 / (1 + |I(p) - I(p - r)| / edge_sigma) (mean absolute RGB difference), never below p1, so depth may jump where
// the image does (occlusion boundaries) while faint, texture-poor surfaces are pulled to smooth depth.
// p1 and p2 are set against the default cost, whose largest per-view value (CostRange) is 0.86; PenaltiesForCost
// scales them with the range of the cost actually built.
struct SgmOptions {
  float p1 = 0.1f;  // in units of the default cost (a per-view mean, see CostOptions)
  float p2 = 1.0f;
  float edge_sigma = 0.02f;
};

// `options` with p1 and p2 multiplied by CostRange(cost) / CostRange(CostOptions()). The automatic detail weight
// leaves the detail term out of full-size lenslet decodes (detail_weight.h), which takes the cost's range from 0.86
// to 0.36; with unscaled penalties, smoothness then outweighs the data 2.4 times more than the penalties were set
// for. Measured on the full-size F01 two-horses capture's decode (central 7x7 views, BadPix 0.07): unscaled 4.79 %,
// scaled 3.70 % (the ideal light field: 2.36 %).
SgmOptions PenaltiesForCost(const SgmOptions& options, const CostOptions& cost);

// Returns the sum over the directions of the path costs, the same shape as `cost`. `guide` is the CV_32FC3 centre
// view of the cost volume's size; the volume needs at least 2 labels (lfsp::Error otherwise).
CostVolume AggregateSemiGlobal(const CostVolume& cost, const cv::Mat& guide, const SgmOptions& options);

// How many scanline directions AggregateSemiGlobal sums: each data cost appears that many times in its output.
constexpr int SemiGlobalPaths() { return 8; }

}  // namespace lfsp::depth
