// The HCI benchmark scene loads as 9x9x512x512x3 and its ground-truth PFM is read the right way up and with the
// right sign: warping views into the centre with it gives a small photometric error, and a clearly larger one with
// the sign flipped or the map upside down (docs/DESIGN.md conventions, checked on real data).

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "lfsp/core/conventions.h"
#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "test_support.h"

namespace lfsp {
namespace {

// Mean absolute difference between the centre view and view `view` warped into it with `disparity`
// (each centre pixel (x, y) sampled at (x - (u-uc)d, y - (v-vc)d)), over pixels 20 px from the border.
double WarpError(const LightField& light_field, const DisparityMap& disparity, ViewIndex view) {
  const LightFieldShape& shape = light_field.shape();
  const ViewIndex centre = shape.Centre();
  cv::Mat map_x(shape.height, shape.width, CV_32FC1);
  cv::Mat map_y(shape.height, shape.width, CV_32FC1);
  for (int y = 0; y < shape.height; ++y) {
    for (int x = 0; x < shape.width; ++x) {
      const PixelPosition p =
          ProjectFromCentre({static_cast<float>(x), static_cast<float>(y)}, disparity.at(y, x), view, centre);
      map_x.at<float>(y, x) = p.x;
      map_y.at<float>(y, x) = p.y;
    }
  }
  cv::Mat warped;
  cv::remap(light_field.View(view), warped, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  const cv::Rect inner(20, 20, shape.width - 40, shape.height - 40);
  cv::Mat difference;
  cv::absdiff(warped(inner), light_field.View(centre)(inner), difference);
  const cv::Scalar mean = cv::mean(difference);
  return (mean[0] + mean[1] + mean[2]) / 3.0;
}

DisparityMap Transformed(const DisparityMap& disparity, bool negate, bool flip_rows) {
  DisparityMap out(disparity.width(), disparity.height());
  for (int y = 0; y < disparity.height(); ++y)
    for (int x = 0; x < disparity.width(); ++x) {
      const float value = disparity.at(flip_rows ? disparity.height() - 1 - y : y, x);
      out.at(y, x) = negate ? -value : value;
    }
  return out;
}

TEST(HciAntinous, LoadsNineByNineViewsOf512WithMetadata) {
  LFSP_REQUIRE_SHARED_DATA(shared);
  const Bundle bundle = LoadLightField(shared / "hci" / "antinous");
  EXPECT_EQ(bundle.light_field.shape(), (LightFieldShape{9, 9, 512, 512, 3}));
  const auto range = DisparityRangeFromMetadata(bundle.light_field.metadata);
  ASSERT_TRUE(range.has_value());
  EXPECT_FLOAT_EQ(range->min, -3.3f);
  EXPECT_FLOAT_EQ(range->max, 2.8f);
  ASSERT_TRUE(bundle.disparity.has_value());  // gt_disp_lowres.pfm beside the views
  EXPECT_EQ(bundle.disparity->width(), 512);
}

TEST(HciAntinous, GroundTruthDisparityHasTheRightOrientationAndSign) {
  LFSP_REQUIRE_SHARED_DATA(shared);
  const Bundle bundle = LoadLightField(shared / "hci" / "antinous");
  const DisparityMap truth = ReadPfm(shared / "hci" / "antinous" / "gt_disp_lowres.pfm");
  for (const ViewIndex view : {ViewIndex{0, 0}, ViewIndex{8, 8}, ViewIndex{8, 0}}) {
    const double right = WarpError(bundle.light_field, truth, view);
    const double negated = WarpError(bundle.light_field, Transformed(truth, true, false), view);
    const double upside_down = WarpError(bundle.light_field, Transformed(truth, false, true), view);
    RecordProperty("warp_error_" + std::to_string(view.u) + "_" + std::to_string(view.v), std::to_string(right));
    EXPECT_LT(right, 0.02) << "corner view (" << view.u << "," << view.v << ")";
    EXPECT_LT(right * 3.0, negated) << "sign: right " << right << " vs negated " << negated;
    EXPECT_LT(right * 2.0, upside_down) << "orientation: right " << right << " vs upside down " << upside_down;
  }
}

}  // namespace
}  // namespace lfsp
