#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/segment/params.h"

namespace lfsp::segment {

// Initial superpixels of the centre view (Algorithm 1, line 2): SLIC over colour, position and disparity, with
// each superpixel connected. `lab` is CV_32FC3, `disparity` CV_32FC1; `disparity_range` = max d - min d (> 0).
// Returns CV_32SC1 labels 0 .. count-1 (every value used) and sets `count`.
cv::Mat CentreSuperpixels(const cv::Mat& lab, const cv::Mat& disparity, double disparity_range,
                          const LfspParams& params, int& count);

// Renumbers the labels of a CV_32SC1 map to 0 .. count-1 in order of first appearance; returns count.
int CompactLabels(cv::Mat& labels);

}  // namespace lfsp::segment
