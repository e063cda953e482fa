// Superpixel metrics on hand-made label maps whose values were computed by hand (see each comment).

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <set>

#include "lfsp/core/error.h"
#include "lfsp/core/rounding.h"
#include "lfsp/segment/metrics.h"

namespace lfsp::segment {
namespace {

// A CV_32SC1 map from rows of labels.
cv::Mat Map(std::initializer_list<std::initializer_list<int>> rows) {
  cv::Mat m(static_cast<int>(rows.size()), static_cast<int>(rows.begin()->size()), CV_32S);
  int y = 0;
  for (const auto& row : rows) {
    int x = 0;
    for (int value : row) m.at<int>(y, x++) = value;
    ++y;
  }
  return m;
}

// Label by column: columns [0, split) get `left`, the rest `right`.
cv::Mat Columns(int width, int height, int split, int left = 0, int right = 1) {
  cv::Mat m(height, width, CV_32S);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) m.at<int>(y, x) = x < split ? left : right;
  }
  return m;
}

TEST(BoundaryRecall, CountsGroundTruthBoundaryPixelsNearASuperpixelBoundary) {
  // GT boundary between columns 3 and 4: boundary pixels are columns 3 and 4, 8 rows -> 16 pixels.
  const cv::Mat gt = Columns(8, 8, 4);
  // Superpixel boundary between columns 5 and 6 (boundary pixels in columns 5, 6): column 4 is 1 px away, column 3
  // is 2 px away.
  const cv::Mat shifted = Columns(8, 8, 6);
  EXPECT_DOUBLE_EQ(BoundaryRecall2D(shifted, gt, 0), 0.0);
  EXPECT_DOUBLE_EQ(BoundaryRecall2D(shifted, gt, 1), 0.5);  // column 4 only: 8 / 16
  EXPECT_DOUBLE_EQ(BoundaryRecall2D(shifted, gt, 2), 1.0);
  EXPECT_DOUBLE_EQ(BoundaryRecall2D(cv::Mat::zeros(8, 8, CV_32S), gt, 2), 0.0);  // no superpixel boundary
  EXPECT_DOUBLE_EQ(BoundaryRecall2D(gt, gt, 0), 1.0);
  EXPECT_DOUBLE_EQ(BoundaryRecall2D(gt, cv::Mat::zeros(8, 8, CV_32S), 2), -1.0);  // undefined: no GT boundary
}

TEST(UndersegmentationError, NeubertProtzelAndPerRegionByHand) {
  // 4x4: GT G0 = columns 0-2 (12 px), G1 = column 3 (4 px); superpixels S0 = columns 0-1 (8 px), S1 = columns 2-3.
  const cv::Mat gt = Columns(4, 4, 3);
  const cv::Mat sp = Columns(4, 4, 2, 10, 20);
  // Neubert-Protzel: S0 n G0 = 8, S0 - G0 = 0 -> 0; S1 n G0 = 4, S1 - G0 = 4 -> 4; S1 n G1 = 4, S1 - G1 = 4 -> 4.
  // (0 + 4 + 4) / 16 = 0.5.
  EXPECT_DOUBLE_EQ(UndersegmentationError2D(sp, gt), 0.5);
  // Per region: G0: S0 inside (0), S1 half inside, not most -> 4; 4 / 12. G1: S1 -> 4; 4 / 4. Mean (1/3 + 1) / 2.
  EXPECT_NEAR(RegionUndersegmentationError2D(sp, gt), 2.0 / 3.0, 1e-12);
  // The ground truth itself has no error.
  EXPECT_DOUBLE_EQ(UndersegmentationError2D(gt, gt), 0.0);
  EXPECT_DOUBLE_EQ(RegionUndersegmentationError2D(gt, gt), 0.0);
}

TEST(UndersegmentationError, IgnoresUnlabelledGroundTruth) {
  // Column 3 unlabelled (-1): only columns 0-2 count. S1 = columns 2-3 then counts only its 4 px in column 2, all
  // inside G0: no error at all.
  cv::Mat gt = Columns(4, 4, 3, 0, -1);
  const cv::Mat sp = Columns(4, 4, 2, 10, 20);
  EXPECT_DOUBLE_EQ(UndersegmentationError2D(sp, gt), 0.0);
  EXPECT_DOUBLE_EQ(AchievableSegmentationAccuracy2D(sp, gt), 1.0);
}

TEST(AchievableSegmentationAccuracy, BestRegionPerSuperpixelByHand) {
  const cv::Mat gt = Columns(4, 4, 3);
  const cv::Mat sp = Columns(4, 4, 2, 10, 20);
  // S0 -> G0: 8; S1 -> max(4, 4) = 4. 12 / 16.
  EXPECT_DOUBLE_EQ(AchievableSegmentationAccuracy2D(sp, gt), 0.75);
  // A 2x3 example with three regions: rows {0 0 1}, {2 2 1}; one superpixel covering everything -> best region
  // has 2 pixels of 6.
  const cv::Mat gt2 = Map({{0, 0, 1}, {2, 2, 1}});
  EXPECT_NEAR(AchievableSegmentationAccuracy2D(cv::Mat::zeros(2, 3, CV_32S), gt2), 2.0 / 6.0, 1e-12);
}

TEST(Compactness, SquaresAndHalvesByHand) {
  // One 4x4 label: area 16, perimeter 16 (image border) -> 4 pi 16 / 256 = pi / 4.
  EXPECT_NEAR(Compactness2D(cv::Mat::zeros(4, 4, CV_32S)), std::numbers::pi / 4.0, 1e-12);
  // Two 4x2 halves: area 8, perimeter 12 each -> 4 pi 8 / 144, weights 1/2 each.
  EXPECT_NEAR(Compactness2D(Columns(4, 4, 2)), 4.0 * std::numbers::pi * 8.0 / 144.0, 1e-12);
}

// A 3x1 light field (views u = 0, 1, 2; centre u = 1) of 8x4 pixels.
LightFieldShape Row3() { return {3, 1, 8, 4, 1}; }

void SetView(Labels& labels, int u, const cv::Mat& map) { map.copyTo(labels.View(ViewIndex{u, 0})); }

TEST(EffectiveLabelRatio, CentreLabelsOverAllLabels) {
  Labels labels(Row3());
  SetView(labels, 0, Columns(8, 4, 4, 0, 2));
  SetView(labels, 1, Columns(8, 4, 4, 0, 1));
  SetView(labels, 2, Columns(8, 4, 4, 0, 1));
  EXPECT_EQ(LabelCount(labels), 3);
  EXPECT_EQ(CentreLabelCount(labels), 2);
  EXPECT_NEAR(EffectiveLabelRatio(labels), 2.0 / 3.0, 1e-12);
}

// Labels far apart (read from a file: -1 for unlabelled, ids in the millions) are counted as dense ones are.
TEST(EffectiveLabelRatio, SparseAndNegativeLabelsCountedLikeDenseOnes) {
  Labels labels(Row3());
  SetView(labels, 0, Columns(8, 4, 4, -1, 2000000000));
  SetView(labels, 1, Columns(8, 4, 4, -2147483647 - 1, 7));
  SetView(labels, 2, Columns(8, 4, 4, 7, -1));
  EXPECT_EQ(LabelCount(labels), 4);  // -1, 7, 2e9, INT32_MIN
  EXPECT_EQ(CentreLabelCount(labels), 2);
  EXPECT_NEAR(EffectiveLabelRatio(labels), 0.5, 1e-12);
}

TEST(SelfSimilarity, ByHandOnAConstantDisparityRow) {
  // Disparity 1 everywhere: centre pixel x0 appears at x0 + 1 in view u = 0 and at x0 - 1 in view u = 2, and a
  // ray at x of view u projects back to x' = x + (u - 1).
  DisparityMap disparity(8, 4, 1.0f);
  const std::vector<DisparityMap> views = PropagateDisparity(disparity, Row3());
  for (const DisparityMap& view : views) EXPECT_FLOAT_EQ(view.at(2, 0), 1.0f);

  // Side views labelled exactly like the centre (ignoring the shift): every slice projects 1 px off in both side
  // views. Label 0: centre centroid 1.5, u = 0 projects columns 0-3 to -1..2 (centroid 0.5): 1 px. All four
  // (label, view) distances are 1 -> SS = 1.
  Labels same(Row3());
  for (int u = 0; u < 3; ++u) SetView(same, u, Columns(8, 4, 4));
  EXPECT_NEAR(SelfSimilarity(same, views), 1.0, 1e-12);
  // In frame only: u = 0 drops label 0's column 0 (x' = -1): centroid of 0..2 = 1.0, 0.5 px; label 1: 1 px.
  // u = 2 drops label 1's column 7 (x' = 8): 5..7 -> 6.0, 0.5 px; label 0: 1 px. Each label: (0.5 + 1) / 2.
  EXPECT_NEAR(SelfSimilarity(same, views, true), 0.75, 1e-12);

  // Consistent labels (side views shifted by the disparity): only the image border moves centroids. u = 0:
  // label 0 = columns 0-4 -> x' -1..3 (centroid 1 vs 1.5), label 1 = 5-7 -> 4..6 (5 vs 5.5); u = 2 mirrors it.
  Labels consistent(Row3());
  SetView(consistent, 0, Columns(8, 4, 5));
  SetView(consistent, 1, Columns(8, 4, 4));
  SetView(consistent, 2, Columns(8, 4, 3));
  EXPECT_NEAR(SelfSimilarity(consistent, views), 0.5, 1e-12);
}

// The evaluation reads both framings from one pass (CarriedCentroidSumsBoth): the same doubles, bit for bit, as
// one pass per framing, so the scores it reports did not move.
TEST(CarriedCentroidSums, BothFramingsFromOnePassAreTheSameDoubles) {
  DisparityMap disparity(8, 4, 1.25f);
  disparity.at(1, 3) = std::numeric_limits<float>::quiet_NaN();
  const std::vector<DisparityMap> views = PropagateDisparity(disparity, Row3());
  Labels labels(Row3());
  SetView(labels, 0, Columns(8, 4, 5));
  SetView(labels, 1, Columns(8, 4, 4, -1, 2));
  SetView(labels, 2, Columns(8, 4, 3));
  const CarriedCentroids both = CarriedCentroidSumsBoth(labels, views);
  std::size_t all_count = 0, in_frame_count = 0;
  const std::vector<double> all = CarriedCentroidSums(labels, views, false, all_count);
  const std::vector<double> in_frame = CarriedCentroidSums(labels, views, true, in_frame_count);
  EXPECT_EQ(both.label_count, all_count);
  EXPECT_EQ(both.label_count, in_frame_count);
  ASSERT_EQ(both.all.size(), all.size());
  ASSERT_EQ(both.in_frame.size(), in_frame.size());
  EXPECT_EQ(std::memcmp(both.all.data(), all.data(), all.size() * sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(both.in_frame.data(), in_frame.data(), in_frame.size() * sizeof(double)), 0);
  EXPECT_NE(both.all, both.in_frame);  // the frame does leave rays out here
  EXPECT_EQ(SelfSimilarityOfSums(both.all, both.label_count, labels.shape()), SelfSimilarity(labels, views));
  EXPECT_EQ(SelfSimilarityOfSums(both.in_frame, both.label_count, labels.shape()), SelfSimilarity(labels, views, true));
}

TEST(LabelsPerPixel, ByHandOnAConstantDisparityRow) {
  // Disparity 2: the side views, labelled like the centre without the shift, show a foreign label to centre pixel
  // x0 = 2 (view 0 at x = 4 has label 1, absent from the centre window 1..3) and to x0 = 5 (view 2 at x = 3 has
  // label 0, absent from 4..6): 2 of 8 pixels per row -> 1 + 0.25.
  DisparityMap disparity(8, 4, 2.0f);
  const std::vector<DisparityMap> views = PropagateDisparity(disparity, Row3());
  Labels same(Row3());
  for (int u = 0; u < 3; ++u) SetView(same, u, Columns(8, 4, 4));
  EXPECT_NEAR(LabelsPerPixel(same, disparity, views), 1.25, 1e-12);
  // Consistent labels: 1 exactly.
  Labels consistent(Row3());
  SetView(consistent, 0, Columns(8, 4, 6));
  SetView(consistent, 1, Columns(8, 4, 4));
  SetView(consistent, 2, Columns(8, 4, 2));
  EXPECT_NEAR(LabelsPerPixel(consistent, disparity, views), 1.0, 1e-12);
}

// Labels per pixel as the definition reads, centre pixel by centre pixel: the labels of the other views' rays that
// see it (through its disparity, where the view's own disparity agrees within 0.5) and that its 3 x 3 centre window
// does not hold, counted once each.
double LabelsPerPixelByDefinition(const Labels& labels, const DisparityMap& centre_disparity,
                                  const std::vector<DisparityMap>& views) {
  const LightFieldShape& shape = labels.shape();
  const ViewIndex c = shape.Centre();
  double total = 0.0;
  for (int y0 = 0; y0 < shape.height; ++y0)
    for (int x0 = 0; x0 < shape.width; ++x0) {
      const float d = centre_disparity.at(y0, x0);
      if (!std::isfinite(d)) continue;
      std::set<std::int32_t> window, foreign;
      for (int y = std::max(0, y0 - 1); y <= std::min(shape.height - 1, y0 + 1); ++y)
        for (int x = std::max(0, x0 - 1); x <= std::min(shape.width - 1, x0 + 1); ++x)
          window.insert(labels.at(c, y, x));
      for (int cam = 0; cam < static_cast<int>(shape.Views()); ++cam) {
        const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
        if (view == c) continue;
        const int x = RoundHalfAway(x0 - (view.u - c.u) * d), y = RoundHalfAway(y0 - (view.v - c.v) * d);
        if (x < 0 || y < 0 || x >= shape.width || y >= shape.height) continue;
        if (std::abs(views[static_cast<std::size_t>(cam)].at(y, x) - d) > 0.5f) continue;
        if (!window.count(labels.at(view, y, x))) foreign.insert(labels.at(view, y, x));
      }
      total += static_cast<double>(foreign.size());
    }
  return 1.0 + total / (static_cast<double>(shape.width) * shape.height);
}

// The banded, view-by-view count gives the definition's value on random labels and disparities (two surfaces, so
// some rays are occluded, and a few unknown disparities), with a view size that is not a multiple of the band.
TEST(LabelsPerPixel, MatchesTheDefinitionOnRandomLabels) {
  std::mt19937 random(41);
  std::uniform_int_distribution<int> id(0, 5);
  std::uniform_real_distribution<float> near(0.9f, 1.6f), far(-1.2f, -0.4f);
  const LightFieldShape shape{5, 5, 27, 19, 1};
  DisparityMap disparity(shape.width, shape.height);
  for (int y = 0; y < shape.height; ++y)
    for (int x = 0; x < shape.width; ++x)
      disparity.at(y, x) =
          (x + y) % 11 == 0 ? std::numeric_limits<float>::quiet_NaN() : (x < 12 ? near(random) : far(random));
  const std::vector<DisparityMap> views = PropagateDisparity(disparity, shape);
  Labels labels(shape);
  for (std::size_t i = 0; i < labels.size(); ++i) labels.data()[i] = id(random);
  const double count = LabelsPerPixel(labels, disparity, views);
  EXPECT_GT(count, 1.5);
  EXPECT_EQ(count, LabelsPerPixelByDefinition(labels, disparity, views));
}

TEST(Metrics4D, AverageOverViews) {
  // View 0 perfect (UE 0), view 1 like the hand example (UE 0.5), view 2 perfect: mean 1/6.
  Labels gt(Row3()), sp(Row3());
  for (int u = 0; u < 3; ++u) SetView(gt, u, Columns(8, 4, 6));
  SetView(sp, 0, Columns(8, 4, 6));
  SetView(sp, 1, Columns(8, 4, 4, 5, 7));
  SetView(sp, 2, Columns(8, 4, 6));
  // View 1: GT G0 = columns 0-5 (24 px), G1 = 6-7 (8 px); S5 = 0-3 inside G0 (0); S7 = 4-7: overlaps G0 by 8 and G1
  // by 8 -> 8 + 8 = 16 -> 16 / 32 = 0.5.
  EXPECT_NEAR(UndersegmentationError(sp, gt), 0.5 / 3.0, 1e-12);
  EXPECT_NEAR(AchievableSegmentationAccuracy(sp, gt), (1.0 + 24.0 / 32.0 + 1.0) / 3.0, 1e-12);
  EXPECT_THROW(UndersegmentationError(sp, Labels(LightFieldShape{3, 1, 4, 4, 1})), Error);
  // The three scores from one count of the overlaps: the same values as the functions (a view without ground truth,
  // all -1, is skipped by both).
  gt.View(ViewIndex{2, 0}).setTo(-1);
  const OverlapScores scores = ScoreOverlaps(sp, gt);
  EXPECT_EQ(scores.undersegmentation_error, UndersegmentationError(sp, gt));
  EXPECT_EQ(scores.region_undersegmentation_error, RegionUndersegmentationError(sp, gt));
  EXPECT_EQ(scores.achievable_segmentation_accuracy, AchievableSegmentationAccuracy(sp, gt));
  EXPECT_NEAR(scores.undersegmentation_error, 0.5 / 2.0, 1e-12);
  EXPECT_THROW(ScoreOverlaps(sp, Labels(LightFieldShape{3, 1, 4, 4, 1})), Error);
}

}  // namespace
}  // namespace lfsp::segment
