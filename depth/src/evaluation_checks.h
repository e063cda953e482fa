#pragma once

#include <opencv2/core/mat.hpp>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/light_field.h"

namespace lfsp::depth {

// The checks every depth figure makes of its inputs (metrics.cc, region_metrics.cc): lfsp::Error naming the sizes.
inline void CheckSameSize(const DisparityMap& algo, const DisparityMap& gt) {
  if (algo.empty() || gt.empty()) throw Error("depth evaluation: empty disparity map");
  if (algo.width() != gt.width() || algo.height() != gt.height())
    throw Error("depth evaluation: algorithm result is " + std::to_string(algo.width()) + "x" +
                std::to_string(algo.height()) + " but the ground truth is " + std::to_string(gt.width()) + "x" +
                std::to_string(gt.height()));
}

inline void CheckRegion(const DisparityMap& gt, const cv::Mat& region) {
  if (region.rows != gt.height() || region.cols != gt.width() || region.type() != CV_8U)
    throw Error("depth evaluation: region mask must be an 8-bit map of the ground truth's size");
}

}  // namespace lfsp::depth
