#include "camera_colour.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <opencv2/core.hpp>

namespace lfsp::testing {

void CheckCameraColour(const LightField& camera, const LightField& truth, const std::string& what, double max_clipped) {
  const cv::Mat decoded = camera.View(camera.shape().Centre()), ideal = truth.View(truth.shape().Centre());
  ASSERT_EQ(decoded.size(), ideal.size()) << what;
  double decoded_sum[3] = {0, 0, 0}, truth_sum[3] = {0, 0, 0};
  long clipped = 0;
  for (int y = 0; y < decoded.rows; ++y)
    for (int x = 0; x < decoded.cols; ++x) {
      const auto& d = decoded.at<cv::Vec3f>(y, x);
      const auto& t = ideal.at<cv::Vec3f>(y, x);
      for (int c = 0; c < 3; ++c) {
        decoded_sum[c] += SrgbToLinear(d[c]);
        truth_sum[c] += t[c];
        clipped += d[c] <= 0.0f ? 1 : 0;
      }
    }
  double ratio[3];
  for (int c = 0; c < 3; ++c) ratio[c] = decoded_sum[c] / truth_sum[c];
  const double mean_ratio = (ratio[0] + ratio[1] + ratio[2]) / 3.0;
  const double clipped_share = static_cast<double>(clipped) / (3.0 * static_cast<double>(decoded.total()));
  std::printf("%s: camera colour / truth per channel %.4f %.4f %.4f, clipped at black %.4f %%\n", what.c_str(),
              ratio[0], ratio[1], ratio[2], 100.0 * clipped_share);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ratio[c] / mean_ratio, 1.0, 0.05) << what << " channel " << c;
  EXPECT_LT(clipped_share, max_clipped) << what;
}

}  // namespace lfsp::testing
