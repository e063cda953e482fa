// The light-field shear of core (lfsp/core/shear.h): sign convention, round trips, labels, weights.

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/shear.h"
#include "lfsp/edit/image_measures.h"
#include "synthetic_light_field.h"

namespace lfsp {
namespace {

using edit::testing::RenderPlane;
using edit::testing::Texture;

constexpr int kViews = 9;
constexpr int kSize = 80;

// A centred square of the view, `margin` pixels in from every edge.
cv::Mat Interior(int size, int margin) {
  cv::Mat mask(size, size, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(margin, margin, size - 2 * margin, size - 2 * margin)).setTo(255);
  return mask;
}

TEST(ShearTest, ShiftIsViewOffsetTimesDisparity) {
  const ImageShift shift = ShearShift({7, 1}, {4, 4}, 0.5f);
  EXPECT_FLOAT_EQ(shift.dx, 1.5f);
  EXPECT_FLOAT_EQ(shift.dy, -1.5f);
}

// Shearing by s moves a plane at disparity d to disparity d - s: every view of the result equals the analytic
// rendering of the plane at d - s, up to interpolation error (the texture has wavelengths down to 5.7 px, so
// bilinear interpolation loses a few percent of contrast at fractional shifts; Keys cubic much less).
TEST(ShearTest, ShearSubtractsDisparity) {
  const float d = 1.3f;
  const float s = 0.55f;
  const LightField plane = RenderPlane(d, kViews, kSize);
  const LightField linear = ShearLightField(plane, s);
  const LightField cubic = ShearLightField(plane, s, {ShearInterpolation::kCubic, true});
  const LightField expected = RenderPlane(d - s, kViews, kSize);
  const cv::Mat interior = Interior(kSize, 4 * 2 + 2);  // the largest shift is 4 * 0.55 px
  for (int v = 0; v < kViews; ++v)
    for (int u = 0; u < kViews; ++u) {
      EXPECT_GT(edit::Psnr(expected.View({u, v}), linear.View({u, v}), interior), 32.0) << "view " << u << "," << v;
      EXPECT_GT(edit::Psnr(expected.View({u, v}), cubic.View({u, v}), interior), 42.0) << "view " << u << "," << v;
    }
  // The wrong sign (shearing the other way) would leave the plane at d + s: far from the expectation.
  const LightField wrong_way = RenderPlane(d + s, kViews, kSize);
  EXPECT_LT(edit::Psnr(wrong_way.View({0, 0}), linear.View({0, 0}), interior), 20.0);
}

// At s = d the plane is aligned: every view equals the centre view.
TEST(ShearTest, ShearAtPlaneDisparityAlignsViews) {
  const float d = -0.8f;
  const LightField sheared = ShearLightField(RenderPlane(d, kViews, kSize), d, {ShearInterpolation::kCubic, true});
  const cv::Mat centre = sheared.View(sheared.shape().Centre());
  const cv::Mat interior = Interior(kSize, 6);
  for (int v = 0; v < kViews; ++v)
    for (int u = 0; u < kViews; ++u) EXPECT_GT(edit::Psnr(centre, sheared.View({u, v}), interior), 45.0);
}

// An integer shear is an exact pixel shift; shearing back restores the interior bit-identically.
TEST(ShearTest, IntegerShearRoundTripIsExact) {
  const LightField original = RenderPlane(0.4f, kViews, kSize);
  const LightField back = ShearLightField(ShearLightField(original, 1.0f), -1.0f);
  const int margin = 4;  // the largest shift
  for (int v = 0; v < kViews; ++v)
    for (int u = 0; u < kViews; ++u) {
      cv::Mat difference;
      const cv::Rect inner(margin, margin, kSize - 2 * margin, kSize - 2 * margin);
      cv::absdiff(original.View({u, v})(inner), back.View({u, v})(inner), difference);
      double max_difference = 0.0;
      cv::minMaxLoc(difference.reshape(1), nullptr, &max_difference);
      EXPECT_EQ(max_difference, 0.0) << "view " << u << "," << v;
    }
}

// Shear then unshear by a fractional amount returns the original within interpolation error: cubic keeps the
// interior above 40 dB, bilinear (which blurs twice) above 28 dB, and cubic is the better of the two.
TEST(ShearTest, FractionalShearRoundTripWithinInterpolationError) {
  const LightField original = RenderPlane(0.4f, kViews, kSize);
  const float s = 0.7f;
  const cv::Mat interior = Interior(kSize, 4);  // 4 * 0.7 px, rounded up
  const LightField cubic = ShearLightField(ShearLightField(original, s, {ShearInterpolation::kCubic, true}), -s,
                                           {ShearInterpolation::kCubic, true});
  const LightField linear = ShearLightField(ShearLightField(original, s), -s);
  double worst_cubic = 1e9;
  double worst_linear = 1e9;
  for (int v = 0; v < kViews; ++v)
    for (int u = 0; u < kViews; ++u) {
      worst_cubic = std::min(worst_cubic, edit::Psnr(original.View({u, v}), cubic.View({u, v}), interior));
      worst_linear = std::min(worst_linear, edit::Psnr(original.View({u, v}), linear.View({u, v}), interior));
    }
  EXPECT_GT(worst_cubic, 40.0);
  EXPECT_GT(worst_linear, 28.0);
  EXPECT_GT(worst_cubic, worst_linear);
}

// Weights mark the rays whose source fell outside the view: 0 there, 1 well inside, partial on the boundary pixel.
TEST(ShearTest, WeightsAreZeroWhereTheSourceIsOutside) {
  const LightField sheared = ShearLightField(RenderPlane(0.0f, 5, 32), 1.5f);
  ASSERT_TRUE(sheared.HasWeights());
  // View u = 4 (offset +2) moves right by 3 px: columns 0..2 come from outside, column 3 from the first column.
  const Array4D<float>& weights = sheared.weights();
  EXPECT_FLOAT_EQ(weights.at({4, 2}, 10, 2), 0.0f);
  EXPECT_FLOAT_EQ(weights.at({4, 2}, 10, 3), 1.0f);
  EXPECT_FLOAT_EQ(weights.at({4, 2}, 10, 20), 1.0f);
  // View u = 3 (offset +1) moves right by 1.5 px: column 0 samples source -1.5 (outside), column 1 samples -0.5
  // (half of its bilinear footprint outside), column 2 samples 0.5 (inside).
  EXPECT_FLOAT_EQ(weights.at({3, 2}, 10, 0), 0.0f);
  EXPECT_FLOAT_EQ(weights.at({3, 2}, 10, 1), 0.5f);
  EXPECT_FLOAT_EQ(weights.at({3, 2}, 10, 2), 1.0f);
  // Input weights are carried: a ray weighted 0.25 keeps that weight where its source is inside.
  LightField weighted = RenderPlane(0.0f, 5, 32);
  weighted.EnableWeights(0.25f);
  EXPECT_FLOAT_EQ(ShearLightField(weighted, 1.0f).weights().at({3, 2}, 10, 10), 0.25f);
}

// Labels shear with nearest-neighbour sampling: the label of view (u, v) at (x, y) after a shear by s is the input
// label at (round(x - (u-uc) s), round(y - (v-vc) s)), -1 outside.
TEST(ShearTest, LabelsShearNearestNeighbour) {
  LightFieldShape shape{5, 3, 20, 12, 1};
  Labels labels(shape);
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u)
      for (int y = 0; y < shape.height; ++y)
        for (int x = 0; x < shape.width; ++x) labels.at({u, v}, y, x) = 1000 * (v * shape.nu + u) + 50 * y + x;
  for (const float s : {0.0f, 0.4f, -1.6f, 2.0f}) {
    const Labels sheared = ShearLabels(labels, s);
    for (int v = 0; v < shape.nv; ++v)
      for (int u = 0; u < shape.nu; ++u)
        for (int y = 0; y < shape.height; ++y)
          for (int x = 0; x < shape.width; ++x) {
            const int sx = static_cast<int>(std::floor(static_cast<float>(x) - (u - 2) * s + 0.5f));
            const int sy = static_cast<int>(std::floor(static_cast<float>(y) - (v - 1) * s + 0.5f));
            const bool inside = sx >= 0 && sy >= 0 && sx < shape.width && sy < shape.height;
            ASSERT_EQ(sheared.at({u, v}, y, x), inside ? labels.at({u, v}, sy, sx) : Labels::kUnlabelled)
                << "s " << s << " view " << u << "," << v << " pixel " << x << "," << y;
          }
  }
}

TEST(ShearTest, DisparityMapShiftsBySAndKeepsNonFinite) {
  DisparityMap disparity(3, 2, 1.25f);
  disparity.at(1, 2) = std::nanf("");
  const DisparityMap sheared = ShearDisparity(disparity, 0.5f);
  EXPECT_FLOAT_EQ(sheared.at(0, 0), 0.75f);
  EXPECT_TRUE(std::isnan(sheared.at(1, 2)));
}

TEST(ShearTest, BadInputThrows) {
  EXPECT_THROW(ShearLightField(LightField(), 1.0f), Error);
  const LightField plane = RenderPlane(0.0f, 3, 16);
  EXPECT_THROW(ShearLightField(plane, std::nanf("")), Error);
  cv::Mat out;
  EXPECT_THROW(TranslateImage(cv::Mat(4, 4, CV_8UC1), {1.0f, 0.0f}, out), Error);
}

}  // namespace
}  // namespace lfsp
