// Shift-and-sum refocusing, focal stacks and all-in-focus images on analytic light fields with known ground truth.

#include "lfsp/edit/refocus.h"

#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/edit/image_measures.h"
#include "synthetic_light_field.h"
#include "test_support.h"

namespace lfsp::edit {
namespace {

using testing::RenderPlane;
using testing::RenderPlanes;
using testing::TwoPlaneScene;

constexpr int kViews = 9;
constexpr int kSize = 96;

// Refocusing a textured plane at its own disparity aligns all 81 rays of every point: the result is the centre
// view (sharp), up to bilinear interpolation error of the texture (PSNR > 35 dB over the whole image, borders
// included, where fewer views contribute; defocused by 0.5 px/view it drops below 25 dB, see below).
TEST(RefocusTest, AtThePlaneDisparityReproducesTheCentreView) {
  const float d = 1.3f;
  const LightField plane = RenderPlane(d, kViews, kSize);
  const cv::Mat centre = plane.View(plane.shape().Centre());
  const cv::Mat refocused = RefocusImage(plane, d);
  EXPECT_GT(Psnr(centre, refocused), 35.0);
  RefocusOptions cubic;
  cubic.interpolation = ShearInterpolation::kCubic;
  EXPECT_GT(Psnr(centre, RefocusImage(plane, d, cubic)), 40.0);  // sharper interpolation, smaller error
}

// Anywhere else the plane is defocused: lower gradient energy (sharpness) than the in-focus image, and blurrier
// the further the focus is from the plane.
TEST(RefocusTest, AwayFromThePlaneDisparityIsBlurred) {
  const float d = 1.3f;
  const LightField plane = RenderPlane(d, kViews, kSize);
  const double sharp = GradientEnergy(RefocusImage(plane, d));
  const double near_miss = GradientEnergy(RefocusImage(plane, d - 0.5f));
  const double far_miss = GradientEnergy(RefocusImage(plane, d - 1.5f));
  EXPECT_LT(near_miss, 0.5 * sharp);
  EXPECT_LT(far_miss, near_miss);
  const cv::Mat centre = plane.View(plane.shape().Centre());
  EXPECT_LT(Psnr(centre, RefocusImage(plane, d - 0.5f)), 25.0);
}

// A focal stack through the plane is sharpest at the slice nearest the plane.
TEST(RefocusTest, FocalStackIsSharpestAtThePlane) {
  const float d = -0.6f;
  const LightField plane = RenderPlane(d, kViews, kSize);
  const std::vector<float> disparities = EvenlySpacedDisparities(-2.0f, 2.0f, 11);  // step 0.4: -0.8, -0.4, ...
  const std::vector<cv::Mat> stack = FocalStack(plane, disparities);
  ASSERT_EQ(stack.size(), disparities.size());
  std::size_t sharpest = 0;
  for (std::size_t i = 1; i < stack.size(); ++i)
    if (GradientEnergy(stack[i]) > GradientEnergy(stack[sharpest])) sharpest = i;
  EXPECT_NEAR(disparities[sharpest], d, 0.2f + 1e-4f);
}

TEST(RefocusTest, EvenlySpacedDisparities) {
  const std::vector<float> four = EvenlySpacedDisparities(-1.5f, 1.5f, 4);
  ASSERT_EQ(four.size(), 4u);
  EXPECT_FLOAT_EQ(four[0], -1.5f);
  EXPECT_FLOAT_EQ(four[1], -0.5f);
  EXPECT_FLOAT_EQ(four[3], 1.5f);
  EXPECT_EQ(EvenlySpacedDisparities(0.0f, 2.0f, 1), std::vector<float>{1.0f});
  EXPECT_THROW(EvenlySpacedDisparities(1.0f, 0.0f, 3), Error);
  EXPECT_THROW(EvenlySpacedDisparities(0.0f, 1.0f, 0), Error);
}

// Ray weights take part: zero-weight rays are ignored, so corrupting them does not change the result.
TEST(RefocusTest, ZeroWeightRaysAreIgnored) {
  const float d = 0.7f;
  LightField plane = RenderPlane(d, 5, 48);
  const cv::Mat clean = RefocusImage(plane, d);
  plane.EnableWeights(1.0f);
  for (int u = 0; u < 5; u += 2) {  // views u = 0, 2, 4 of row v = 1: garbage with weight 0
    plane.View({u, 1}).setTo(cv::Scalar::all(1.0));
    plane.WeightView({u, 1}).setTo(cv::Scalar(0.0));
  }
  // Removing views changes the average only by the interpolation error of the remaining ones.
  EXPECT_GT(Psnr(clean, RefocusImage(plane, d)), 40.0);
  RefocusOptions cubic;
  cubic.interpolation = ShearInterpolation::kCubic;
  EXPECT_GT(Psnr(RefocusImage(RenderPlane(d, 5, 48), d, cubic), RefocusImage(plane, d, cubic)), 40.0);
  RefocusOptions unweighted;
  unweighted.use_ray_weights = false;
  EXPECT_LT(Psnr(clean, RefocusImage(plane, d, unweighted)), 25.0);
}

// Two planes: a textured rectangle at d = 1.5 in front of a textured background at d = -1. The all-in-focus image
// from the true disparity map matches the sharp texture (the centre view) on both planes, whereas refocusing at
// either plane blurs the other.
// The same light field gives the same bytes whatever the thread count (the pipeline's focal stack is compared byte
// for byte with `lfsp refocus`'s, and per-thread sums merged in finishing order made them differ): bilinear and
// cubic refocus, and the all-in-focus image, with 1, 2, 3 and 5 threads.
TEST(RefocusTest, SameBytesForEveryThreadCount) {
  TwoPlaneScene scene;
  Labels labels;
  DisparityMap disparity;
  const LightField light_field = RenderPlanes(scene, kViews, kSize, &labels, &disparity);
  RefocusOptions cubic;
  cubic.interpolation = ShearInterpolation::kCubic;
  const auto images = [&] {
    return std::vector<cv::Mat>{RefocusImage(light_field, 0.37f), RefocusImage(light_field, -1.21f, cubic),
                                AllInFocus(light_field, disparity)};
  };
  const int previous = omp_get_max_threads();
  omp_set_num_threads(1);
  const std::vector<cv::Mat> reference = images();
  for (const int threads : {2, 3, 5}) {
    omp_set_num_threads(threads);
    const std::vector<cv::Mat> again = images();
    for (std::size_t k = 0; k < reference.size(); ++k) {
      ASSERT_EQ(again[k].size(), reference[k].size());
      const std::size_t bytes = reference[k].total() * reference[k].elemSize();
      EXPECT_EQ(std::memcmp(again[k].data, reference[k].data, bytes), 0)
          << "image " << k << ", " << threads << " threads";
    }
  }
  omp_set_num_threads(previous);
}

TEST(AllInFocusTest, TwoPlaneSceneIsSharpOnBothPlanes) {
  TwoPlaneScene scene;
  scene.x0 = 30.0f;
  scene.y0 = 26.0f;
  scene.x1 = 70.0f;
  scene.y1 = 64.0f;
  Labels labels;
  DisparityMap disparity;
  const LightField light_field = RenderPlanes(scene, kViews, kSize, &labels, &disparity);
  const cv::Mat centre = light_field.View(light_field.shape().Centre());
  const cv::Mat centre_labels = labels.View(labels.shape().Centre());
  const cv::Mat foreground = centre_labels == 1;
  const cv::Mat background = centre_labels == 0;

  const cv::Mat sharp = AllInFocus(light_field, disparity);
  EXPECT_GT(Psnr(centre, sharp, foreground), 35.0);
  EXPECT_GT(Psnr(centre, sharp, background), 35.0);  // includes the pixels beside the occluding edge

  const cv::Mat at_foreground = RefocusImage(light_field, scene.foreground_disparity);
  const cv::Mat at_background = RefocusImage(light_field, scene.background_disparity);
  EXPECT_LT(Psnr(centre, at_foreground, background), 25.0);
  EXPECT_LT(Psnr(centre, at_background, foreground), 25.0);
  EXPECT_GT(GradientEnergy(sharp, background), 2.0 * GradientEnergy(at_foreground, background));
  EXPECT_GT(GradientEnergy(sharp, foreground), 2.0 * GradientEnergy(at_background, foreground));
}

// Without occlusion handling the background beside the foreground edge mixes in foreground colour; with it, the
// background band next to the edge is reproduced markedly better.
TEST(AllInFocusTest, OcclusionHandlingCleansTheBackgroundBesideEdges) {
  TwoPlaneScene scene;
  scene.x0 = 30.0f;
  scene.y0 = 26.0f;
  scene.x1 = 70.0f;
  scene.y1 = 64.0f;
  Labels labels;
  DisparityMap disparity;
  const LightField light_field = RenderPlanes(scene, kViews, kSize, &labels, &disparity);
  const cv::Mat centre = light_field.View(light_field.shape().Centre());
  // The background band within 10 px of the rectangle: the rays the foreground hides in some views.
  cv::Mat band(kSize, kSize, CV_8UC1, cv::Scalar(0));
  band(cv::Rect(20, 16, 60, 58)).setTo(255);
  band(cv::Rect(30, 26, 40, 38)).setTo(0);

  AllInFocusOptions naive;
  naive.occlusion_aware = false;
  const double aware_psnr = Psnr(centre, AllInFocus(light_field, disparity), band);
  const double naive_psnr = Psnr(centre, AllInFocus(light_field, disparity, naive), band);
  EXPECT_GT(aware_psnr, 35.0);
  EXPECT_GT(aware_psnr, naive_psnr + 5.0);
}

TEST(AllInFocusTest, NonFiniteDisparityKeepsTheCentreView) {
  const LightField plane = RenderPlane(0.5f, 5, 32);
  DisparityMap disparity(32, 32, std::nanf(""));
  const cv::Mat out = AllInFocus(plane, disparity);
  EXPECT_TRUE(std::isinf(Psnr(plane.View(plane.shape().Centre()), out)));
}

TEST(AllInFocusTest, DisparitySizeMismatchThrows) {
  const LightField plane = RenderPlane(0.5f, 3, 16);
  EXPECT_THROW(AllInFocus(plane, DisparityMap(15, 16)), Error);
  EXPECT_THROW(RefocusImage(LightField(), 0.0f), Error);
}

// Real data: the HCI scene antinous with its ground-truth disparity. The all-in-focus image reproduces the centre
// view (the scene is nearly Lambertian), and a refocused image is sharp exactly where the scene lies at that
// disparity.
TEST(RefocusRealDataTest, AntinousAllInFocusAndRefocus) {
  LFSP_REQUIRE_SHARED_DATA(shared);
  const Bundle bundle = LoadLightField(shared / "hci" / "antinous");
  ASSERT_TRUE(bundle.disparity.has_value());
  const LightField& light_field = bundle.light_field;
  const cv::Mat centre = light_field.View(light_field.shape().Centre());
  const cv::Mat sharp = AllInFocus(light_field, *bundle.disparity);
  EXPECT_GT(Psnr(centre, sharp), 42.0);  // measured 49 dB

  const float s = 0.0f;
  const cv::Mat in_focus = cv::abs(bundle.disparity->Mat() - s) < 0.05f;
  const cv::Mat far_from_focus = cv::abs(bundle.disparity->Mat() - s) > 1.0f;
  ASSERT_GT(cv::countNonZero(in_focus), 1000);
  const cv::Mat refocused = RefocusImage(light_field, s);
  EXPECT_GT(Psnr(centre, refocused, in_focus), 38.0);  // measured 43.6 dB (31.3 dB far from focus)
  EXPECT_LT(Psnr(centre, refocused, far_from_focus), Psnr(centre, refocused, in_focus) - 8.0);
}

}  // namespace
}  // namespace lfsp::edit
