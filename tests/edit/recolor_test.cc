// Recolouring through light-field superpixels on simulator scenes with ground-truth labels per ray.

#include "lfsp/edit/recolor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/edit/colour_adjust.h"
#include "lfsp/edit/selection.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"
#include "test_support.h"

namespace lfsp::edit {
namespace {

constexpr int kStripesLabel = 2;  // "planes" scene: a striped card partly hidden by the noise card (label 3)

simulate::RenderedLightField RenderPlanesScene() {
  simulate::RenderOptions options;
  options.nu = 9;
  options.nv = 9;
  options.width = 96;
  options.height = 96;
  options.supersampling = 2;
  return simulate::RenderLightField(simulate::BuiltinScene("planes"), options);
}

// The rays that changed between two light fields (any channel differs), per view.
cv::Mat ChangedRays(const LightField& before, const LightField& after, ViewIndex view) {
  cv::Mat difference;
  cv::absdiff(before.View(view), after.View(view), difference);
  std::vector<cv::Mat> channels;
  cv::split(difference, channels);
  return (channels[0] > 0) | (channels[1] > 0) | (channels[2] > 0);
}

double IntersectionOverUnion(const cv::Mat& a, const cv::Mat& b) {
  const double intersection = cv::countNonZero(a & b);
  const double union_count = cv::countNonZero(a | b);
  return union_count == 0 ? 1.0 : intersection / union_count;
}

// Checks the "done means" in every view: the changed rays match the object's ground-truth rays (IoU >= 0.95)
// and no ray outside the edit (strength 0) changed at all (bit-identical).
void ExpectEditMatchesObject(const simulate::RenderedLightField& scene, const LightField& edited,
                             const Labels& superpixels, const std::vector<std::int32_t>& selection, int object) {
  const LightFieldShape& shape = scene.light_field.shape();
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      const ViewIndex view{u, v};
      const cv::Mat changed = ChangedRays(scene.light_field, edited, view);
      const cv::Mat object_rays = scene.labels.View(view) == object;
      EXPECT_GE(IntersectionOverUnion(changed, object_rays), 0.95) << "view " << u << "," << v;
      const cv::Mat selected = EditStrength(superpixels.View(view), selection, 0.0f) > 0.0f;
      EXPECT_EQ(cv::countNonZero(changed & ~selected), 0)
          << "a ray outside the selection changed, view " << u << "," << v;
    }
}

ColourAdjustment Adjustment() {
  ColourAdjustment adjustment;
  adjustment.hue_degrees = 120.0f;
  adjustment.saturation = 1.2f;
  adjustment.value = 0.7f;  // darkening changes every ray that is not black, whatever its hue
  return adjustment;
}

// Ground-truth labels as superpixels, the object chosen by clicking one point of it in the centre view.
TEST(RecolorTest, ClickInCentreViewChangesExactlyTheObjectInEveryView) {
  const simulate::RenderedLightField scene = RenderPlanesScene();
  const std::vector<std::int32_t> selection = SelectAtPoints(scene.labels, {cv::Point(20, 20)});
  ASSERT_EQ(selection, std::vector<std::int32_t>{kStripesLabel});

  LightField edited = scene.light_field;
  RecolorOptions options;
  options.adjustment = Adjustment();
  const RecolorStats stats = Recolor(edited, scene.labels, selection, options);
  EXPECT_GT(stats.selected_rays, 0u);
  EXPECT_EQ(stats.feather_rays, 0u);
  ExpectEditMatchesObject(scene, edited, scene.labels, selection, kStripesLabel);
}

// Superpixels finer than objects, consistent across views (each is one object's surface cut by a grid in centre-view
// coordinates, followed into every view along the true disparity), as a light-field superpixel method would make.
// Selecting the object by a centre-view mask picks its superpixels; parts of the object that the centre view does
// not see belong to superpixels nobody selected, so the IoU is not trivially 1.
Labels GridSuperpixels(const simulate::RenderedLightField& scene, int cell) {
  const LightFieldShape& shape = scene.light_field.shape();
  Labels superpixels(shape);
  const ViewIndex centre = shape.Centre();
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      const DisparityMap& disparity = scene.view_disparity[static_cast<std::size_t>(CameraNumber({u, v}, shape.nu))];
      for (int y = 0; y < shape.height; ++y)
        for (int x = 0; x < shape.width; ++x) {
          const int object = scene.labels.at({u, v}, y, x);
          const float d = disparity.at(y, x);
          // Where this ray's surface point appears in the centre view (inverse of the docs/DESIGN.md projection).
          const float cx = static_cast<float>(x) + static_cast<float>(u - centre.u) * d;
          const float cy = static_cast<float>(y) + static_cast<float>(v - centre.v) * d;
          const int gx = static_cast<int>(std::floor(cx / static_cast<float>(cell))) + 10;
          const int gy = static_cast<int>(std::floor(cy / static_cast<float>(cell))) + 10;
          superpixels.at({u, v}, y, x) = object * 10000 + gy * 100 + gx;
        }
    }
  return superpixels;
}

TEST(RecolorTest, MaskSelectionOfFinerSuperpixelsChangesTheObjectInEveryView) {
  const simulate::RenderedLightField scene = RenderPlanesScene();
  const Labels superpixels = GridSuperpixels(scene, 12);
  const ViewIndex centre = scene.light_field.shape().Centre();
  const cv::Mat mask = scene.labels.View(centre) == kStripesLabel;  // the object as seen in the centre view
  const std::vector<std::int32_t> selection = SelectByMask(superpixels, mask);
  EXPECT_GT(selection.size(), 4u);
  for (const std::int32_t id : selection) EXPECT_EQ(id / 10000, kStripesLabel);

  LightField edited = scene.light_field;
  RecolorOptions options;
  options.adjustment = Adjustment();
  Recolor(edited, superpixels, selection, options);
  ExpectEditMatchesObject(scene, edited, superpixels, selection, kStripesLabel);
}

// Same in HSV, and on a different object (the slanted card, whose disparity varies across it).
TEST(RecolorTest, HsvEditOfASlantedObject) {
  const simulate::RenderedLightField scene = RenderPlanesScene();
  constexpr int kSlanted = 4;
  const std::vector<std::int32_t> selection = SelectLabelIds(scene.labels, {kSlanted});
  LightField edited = scene.light_field;
  RecolorOptions options;
  options.adjustment = Adjustment();
  options.adjustment.space = ColourSpace::kHsv;
  Recolor(edited, scene.labels, selection, options);
  ExpectEditMatchesObject(scene, edited, scene.labels, selection, kSlanted);
}

// Feathering: a soft band of `feather` pixels beside the selection, strength 1 - r / (feather + 1) at distance r,
// scaled by the ray weight; untouched beyond it.
TEST(RecolorTest, FeatherStrengthFollowsDistanceAndWeights) {
  cv::Mat labels(8, 20, CV_32SC1, cv::Scalar(7));
  labels.colRange(0, 10).setTo(cv::Scalar(3));  // label 3 on the left half, 7 on the right
  const cv::Mat hard = EditStrength(labels, {3}, 0.0f);
  EXPECT_FLOAT_EQ(hard.at<float>(4, 9), 1.0f);
  EXPECT_FLOAT_EQ(hard.at<float>(4, 10), 0.0f);

  const cv::Mat soft = EditStrength(labels, {3}, 3.0f);
  EXPECT_FLOAT_EQ(soft.at<float>(4, 9), 1.0f);
  EXPECT_NEAR(soft.at<float>(4, 10), 0.75f, 1e-5f);  // distance 1
  EXPECT_NEAR(soft.at<float>(4, 11), 0.5f, 1e-5f);   // distance 2
  EXPECT_NEAR(soft.at<float>(4, 12), 0.25f, 1e-5f);  // distance 3
  EXPECT_FLOAT_EQ(soft.at<float>(4, 13), 0.0f);      // beyond the band

  const cv::Mat weights(8, 20, CV_32FC1, cv::Scalar(0.5));
  const cv::Mat weighted = EditStrength(labels, {3}, 3.0f, weights);
  EXPECT_FLOAT_EQ(weighted.at<float>(4, 9), 1.0f);  // selected rays: full strength regardless
  EXPECT_NEAR(weighted.at<float>(4, 10), 0.375f, 1e-5f);
}

// Label ids need not be dense: a huge id is selected without a table of that size.
TEST(RecolorTest, HugeLabelIdsAreSelected) {
  cv::Mat labels(4, 4, CV_32SC1, cv::Scalar(5));
  labels.at<std::int32_t>(1, 2) = 2000000000;
  const cv::Mat strength = EditStrength(labels, {2000000000, 7}, 0.0f);
  EXPECT_FLOAT_EQ(strength.at<float>(1, 2), 1.0f);
  EXPECT_EQ(cv::countNonZero(strength), 1);
}

TEST(RecolorTest, FeatheredEditLeavesRaysBeyondTheBandBitIdentical) {
  const simulate::RenderedLightField scene = RenderPlanesScene();
  const std::vector<std::int32_t> selection{kStripesLabel};
  LightField hard_edit = scene.light_field;
  LightField soft_edit = scene.light_field;
  RecolorOptions options;
  options.adjustment = Adjustment();
  Recolor(hard_edit, scene.labels, selection, options);
  options.feather_px = 4.0f;
  const RecolorStats stats = Recolor(soft_edit, scene.labels, selection, options);
  EXPECT_GT(stats.feather_rays, 0u);
  const LightFieldShape& shape = scene.light_field.shape();
  for (int v = 0; v < shape.nv; v += 4)
    for (int u = 0; u < shape.nu; u += 4) {
      const ViewIndex view{u, v};
      const cv::Mat strength = EditStrength(scene.labels.View(view), selection, 4.0f);
      const cv::Mat changed = ChangedRays(scene.light_field, soft_edit, view);
      EXPECT_EQ(cv::countNonZero(changed & (strength == 0.0f)), 0);
      // Selected rays get exactly the hard edit; band rays lie between the original and the full edit.
      const cv::Mat selected = scene.labels.View(view) == kStripesLabel;
      EXPECT_EQ(cv::countNonZero(ChangedRays(hard_edit, soft_edit, view) & selected), 0);
      EXPECT_GT(cv::countNonZero(changed & ~selected), 0);
    }
}

TEST(SelectionTest, MaskSelectsLabelsMostlyInside) {
  LightFieldShape shape{3, 3, 10, 4, 1};
  Labels labels(shape, 0);
  cv::Mat centre = labels.View(shape.Centre());
  centre.colRange(0, 5).setTo(cv::Scalar(1));  // label 1: columns 0-4, label 2: columns 5-9
  centre.colRange(5, 10).setTo(cv::Scalar(2));
  cv::Mat mask(4, 10, CV_8UC1, cv::Scalar(0));
  mask.colRange(0, 3).setTo(255);  // 60 % of label 1
  mask.colRange(5, 7).setTo(255);  // 40 % of label 2
  EXPECT_EQ(SelectByMask(labels, mask), std::vector<std::int32_t>{1});
  mask.colRange(5, 8).setTo(255);  // now 60 % of label 2
  EXPECT_EQ(SelectByMask(labels, mask), (std::vector<std::int32_t>{1, 2}));
  EXPECT_THROW(SelectByMask(labels, cv::Mat(4, 10, CV_8UC1, cv::Scalar(0))), Error);    // nothing selected
  EXPECT_THROW(SelectByMask(labels, cv::Mat(5, 10, CV_8UC1, cv::Scalar(255))), Error);  // wrong size
}

TEST(SelectionTest, PointsAndIdsAreChecked) {
  LightFieldShape shape{3, 3, 10, 4, 1};
  Labels labels(shape, 5);
  labels.at(shape.Centre(), 1, 1) = Labels::kUnlabelled;
  labels.at({0, 0}, 2, 2) = 9;  // only in a side view
  EXPECT_EQ(SelectAtPoints(labels, {cv::Point(3, 2), cv::Point(4, 3)}), std::vector<std::int32_t>{5});
  EXPECT_THROW(SelectAtPoints(labels, {cv::Point(1, 1)}), Error);   // unlabelled
  EXPECT_THROW(SelectAtPoints(labels, {cv::Point(10, 0)}), Error);  // outside
  EXPECT_EQ(SelectLabelIds(labels, {9, 5, 9}), (std::vector<std::int32_t>{5, 9}));
  EXPECT_THROW(SelectLabelIds(labels, {4}), Error);  // occurs nowhere
  EXPECT_THROW(SelectLabelIds(labels, {-1}), Error);
}

// Labels are read alone from a bundle's `labels` dataset; files without one, or not HDF5, are named in the error.
TEST(LabelsFileTest, ReadsTheLabelsDatasetAndRejectsOthers) {
  lfsp::testing::TempDir dir;
  LightFieldShape shape{3, 2, 6, 5, 3};
  Bundle bundle;
  bundle.light_field = LightField(shape);
  WriteBundle(bundle, dir / "no_labels.h5");
  bundle.labels = Labels(shape, 4);
  bundle.labels->at({2, 1}, 4, 5) = 11;
  WriteBundle(bundle, dir / "labels.h5");

  const Labels labels = ReadLabels(dir / "labels.h5");
  EXPECT_EQ(labels.shape().nu, 3);
  EXPECT_EQ(labels.shape().nv, 2);
  EXPECT_EQ(labels.at({2, 1}, 4, 5), 11);
  EXPECT_EQ(labels.at({0, 0}, 0, 0), 4);
  EXPECT_NO_THROW(RequireLabelsMatch(labels, shape, "test"));
  EXPECT_THROW(RequireLabelsMatch(labels, LightFieldShape{2, 3, 6, 5, 3}, "test"), Error);

  try {
    ReadLabels(dir / "no_labels.h5");
    FAIL() << "expected an error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no_labels.h5"), std::string::npos) << error.what();
  }
  lfsp::testing::WriteBytes(dir / "text.h5", "not hdf5");
  EXPECT_THROW(ReadLabels(dir / "text.h5"), Error);
  EXPECT_THROW(ReadLabels(dir / "missing.h5"), Error);
}

TEST(ColourAdjustTest, HsvHueRotationTurnsRedIntoGreen) {
  cv::Mat pixels(1, 1, CV_32FC3, cv::Scalar(1.0, 0.0, 0.0));  // RGB red
  ColourAdjustment adjustment;
  adjustment.space = ColourSpace::kHsv;
  adjustment.hue_degrees = 120.0f;
  AdjustColours(pixels, adjustment, Transfer::kSrgb);
  const cv::Vec3f rgb = pixels.at<cv::Vec3f>(0, 0);
  EXPECT_NEAR(rgb[0], 0.0f, 1e-4f);
  EXPECT_NEAR(rgb[1], 1.0f, 1e-4f);
  EXPECT_NEAR(rgb[2], 0.0f, 1e-4f);
}

// In L*C*h, hue rotates the (a*, b*) angle, saturation scales chroma and value scales lightness, measured back in
// CIELab (a low-chroma colour so the result stays in gamut).
TEST(ColourAdjustTest, LchAdjustmentActsOnHueChromaAndLightness) {
  for (const Transfer transfer : {Transfer::kSrgb, Transfer::kLinear}) {
    const auto code = transfer == Transfer::kSrgb ? cv::COLOR_RGB2Lab : cv::COLOR_LRGB2Lab;
    cv::Mat pixels(1, 1, CV_32FC3, cv::Scalar(0.45, 0.38, 0.3));
    cv::Mat before;
    cv::cvtColor(pixels, before, code);
    ColourAdjustment adjustment;
    adjustment.hue_degrees = 60.0f;
    adjustment.saturation = 1.5f;
    adjustment.value = 0.9f;
    AdjustColours(pixels, adjustment, transfer);
    cv::Mat after;
    cv::cvtColor(pixels, after, code);
    const cv::Vec3f b = before.at<cv::Vec3f>(0, 0);
    const cv::Vec3f a = after.at<cv::Vec3f>(0, 0);
    EXPECT_NEAR(a[0], 0.9f * b[0], 0.3f);
    EXPECT_NEAR(std::hypot(a[1], a[2]), 1.5f * std::hypot(b[1], b[2]), 0.3f);
    const float turn = std::remainder(std::atan2(a[2], a[1]) - std::atan2(b[2], b[1]), 2.0f * 3.14159265f);
    EXPECT_NEAR(turn * 180.0f / 3.14159265f, 60.0f, 1.0f);
  }
}

TEST(ColourAdjustTest, IdentityLeavesValuesBitIdentical) {
  cv::Mat pixels(2, 2, CV_32FC3, cv::Scalar(0.1234567, 0.7654321, 0.5));
  const cv::Mat original = pixels.clone();
  AdjustColours(pixels, ColourAdjustment{}, Transfer::kSrgb);
  EXPECT_EQ(cv::countNonZero(pixels.reshape(1) != original.reshape(1)), 0);
}

TEST(RecolorTest, BadInputThrows) {
  LightFieldShape shape{3, 3, 8, 8, 3};
  LightField light_field(shape);
  Labels labels(LightFieldShape{3, 3, 8, 7, 1}, 0);
  RecolorOptions options;
  EXPECT_THROW(Recolor(light_field, labels, {0}, options), Error);  // size mismatch
  Labels matching(shape, 0);
  EXPECT_THROW(Recolor(light_field, matching, {}, options), Error);  // empty selection
  options.adjustment.saturation = -1.0f;
  EXPECT_THROW(Recolor(light_field, matching, {0}, options), Error);
  options.adjustment.saturation = 1.0f;
  options.feather_px = -2.0f;
  EXPECT_THROW(Recolor(light_field, matching, {0}, options), Error);
}

}  // namespace
}  // namespace lfsp::edit
