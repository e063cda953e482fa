// Sub-label refinement and the slanted-plane fill on inputs with known answers.

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "lfsp/depth/cost_volume.h"
#include "lfsp/depth/plane_fit.h"
#include "lfsp/depth/refinement.h"

namespace lfsp::depth {
namespace {

TEST(SelectDisparity, ParabolaRefinementFindsTheTrueMinimumBetweenLabels) {
  const std::vector<float> labels = LabelDisparities(-1.0f, 1.0f, 21);  // step 0.1
  CostVolume cost(4, 3, 21);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      const float minimum = 7.0f + 0.1f * static_cast<float>(x) + 0.2f * static_cast<float>(y);  // label units
      for (int l = 0; l < 21; ++l) {
        const float t = static_cast<float>(l) - minimum;
        cost.Curve(y, x)[l] = 1.0f + 0.05f * t * t;
      }
    }
  }
  const DisparityEstimate estimate = SelectDisparity(cost, labels);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) {
      const float expected = -1.0f + 0.1f * (7.0f + 0.1f * static_cast<float>(x) + 0.2f * static_cast<float>(y));
      EXPECT_NEAR(estimate.disparity.at(y, x), expected, 1e-4);
      EXPECT_GT(estimate.confidence.at(y, x), 0.0f);
      EXPECT_LE(estimate.confidence.at(y, x), 1.0f);
    }
  }
  // A flat curve has no confidence.
  CostVolume flat(1, 1, 21, 0.5f);
  EXPECT_FLOAT_EQ(SelectDisparity(flat, labels).confidence.at(0, 0), 0.0f);
}

TEST(PlaneFit, UnsupportedPixelsTakeTheirSuperpixelsPlane) {
  // One slanted plane over a plain grey image; a block of wrong, unsupported values inside it.
  const int size = 64;
  DisparityMap disparity(size, size);
  DisparityMap support(size, size, 1.0f);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) disparity.at(y, x) = 0.01f * static_cast<float>(x) - 0.02f * static_cast<float>(y);
  }
  for (int y = 20; y < 28; ++y) {
    for (int x = 30; x < 38; ++x) {
      disparity.at(y, x) = 5.0f;
      support.at(y, x) = 0.0f;
    }
  }
  const cv::Mat guide(size, size, CV_32FC3, cv::Scalar(0.4, 0.4, 0.4));
  PlaneFitRefine(disparity, support, guide, {});
  for (int y = 20; y < 28; ++y) {
    for (int x = 30; x < 38; ++x) {
      EXPECT_NEAR(disparity.at(y, x), 0.01f * static_cast<float>(x) - 0.02f * static_cast<float>(y), 1e-3);
    }
  }
}

}  // namespace
}  // namespace lfsp::depth
