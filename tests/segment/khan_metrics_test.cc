// Khan et al.'s definitions of the superpixel metrics, on hand-made light fields whose values were computed by hand
// (see each comment), each beside lfsp's own definition where the two differ.

#include <gtest/gtest.h>

#include <functional>
#include <opencv2/imgproc.hpp>
#include <random>

#include "lfsp/segment/khan_metrics.h"
#include "lfsp/segment/metrics.h"

namespace lfsp::segment {
namespace {

// A light field of labels, label(view, x, y) for every ray.
Labels MakeLabels(int nu, int nv, int width, int height, const std::function<int(ViewIndex, int, int)>& label) {
  Labels labels(LightFieldShape{nu, nv, width, height, 1});
  for (int v = 0; v < nv; ++v)
    for (int u = 0; u < nu; ++u)
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) labels.at({u, v}, y, x) = label({u, v}, x, y);
  return labels;
}

std::vector<DisparityMap> ConstantDisparity(const LightFieldShape& shape, float d) {
  return std::vector<DisparityMap>(shape.Views(), DisparityMap(shape.width, shape.height, d));
}

TEST(KhanSelfSimilarity, AveragesOverEveryLabelAndViewPairIncludingTheCentre) {
  // 3x3 views of 8x4 at disparity 0: columns 0-3 label 0 (centroid x 1.5), 4-7 label 1 (5.5). In view (0, 0) the
  // boundary moves right by two: label 0 covers 0-5 (2.5), label 1 6-7 (6.5). Both are 1 px off there, 0 elsewhere.
  const Labels labels = MakeLabels(3, 3, 8, 4, [](ViewIndex view, int x, int) {
    const int split = (view.u == 0 && view.v == 0) ? 6 : 4;
    return x < split ? 0 : 1;
  });
  const auto disparity = ConstantDisparity(labels.shape(), 0.0f);
  // Khan: 2 px of error over 9 views x 2 labels = 18 pairs.
  EXPECT_NEAR(KhanSelfSimilarity(labels, disparity), 2.0 / 18.0, 1e-12);
  // LFSP (Eqs. 8-10): per label the mean over the 8 other views (1/8), then over labels.
  EXPECT_NEAR(SelfSimilarity(labels, disparity), 1.0 / 8.0, 1e-12);
}

TEST(KhanSelfSimilarity, CarriesRaysToTheCentreByTheirDisparity) {
  // 3x1 views of 12x1 at disparity 1: ray x of view u lands at c = x + (u - 1) in the centre view, and is labelled
  // by where it lands: 0 for c < 4, 1 for 4 <= c < 8, 2 beyond. Label 1 is consistent (error 0). Labels 0 and 2 are
  // clipped by the border differently in views 0 and 2: label 0 lands on -1..3 (centroid 1) and 1..3 (2) against the
  // centre's 0..3 (1.5); label 2 on 8..10 (9) and 8..12 (10) against 8..11 (9.5). Four errors of 0.5 over 9 pairs.
  const Labels labels = MakeLabels(3, 1, 12, 1, [](ViewIndex view, int x, int) {
    const int landing = x + (view.u - 1);
    return landing < 4 ? 0 : (landing < 8 ? 1 : 2);
  });
  EXPECT_NEAR(KhanSelfSimilarity(labels, ConstantDisparity(labels.shape(), 1.0f)), 2.0 / 9.0, 1e-12);
  // Read with disparity 0 (rays not carried), label 1 is also off, by 1 px in views 0 and 2: 4 / 9.
  EXPECT_NEAR(KhanSelfSimilarity(labels, ConstantDisparity(labels.shape(), 0.0f)), 4.0 / 9.0, 1e-12);
}

TEST(KhanLabelsPerPixel, IsOneForIdenticalViewsAndCountsCentrePixelsAViewCarriesNothingTo) {
  const Labels one = MakeLabels(3, 3, 8, 6, [](ViewIndex, int x, int) { return x / 4; });
  EXPECT_DOUBLE_EQ(KhanLabelsPerPixel(one, ConstantDisparity(one.shape(), 0.0f)), 1.0);
  // Disparity 1 everywhere, one label: view (u, v) carries ray (x, y) to (x + du, y + dv), so the centre pixels it
  // misses are 48 - (8 - |du|)(6 - |dv|): 6 for du = +-1, 8 for dv = +-1, 13 for the four corner views, 80 in all.
  const Labels single = MakeLabels(3, 3, 8, 6, [](ViewIndex, int, int) { return 7; });
  EXPECT_NEAR(KhanLabelsPerPixel(single, ConstantDisparity(single.shape(), 1.0f)), 1.0 + 80.0 / 48.0, 1e-12);
  // lfsp's definition follows each centre pixel only into the views where it is visible: 1.
  EXPECT_DOUBLE_EQ(LabelsPerPixel(single, DisparityMap(8, 6, 1.0f), ConstantDisparity(single.shape(), 1.0f)), 1.0);
}

TEST(KhanLabelsPerPixel, KeepsTheFrontRayWhereTwoLandOnOnePixel) {
  // 3x1 views of 6x1, centre row 0 0 5 5 9 9. In view u = 2 (du = +1), ray 1 (label 5, disparity 1) and ray 2
  // (label 9, disparity 0) both land on centre pixel 2, and the front one (disparity 1, label 5) is kept: label 5 is
  // in pixel 2's neighbourhood, label 9 would not be (it sits at 4 and 5).
  Labels labels(LightFieldShape{3, 1, 6, 1, 1});
  const int centre_row[6] = {0, 0, 5, 5, 9, 9};
  for (int u = 0; u < 3; ++u)
    for (int x = 0; x < 6; ++x) labels.at({u, 0}, 0, x) = centre_row[x];
  labels.at({2, 0}, 0, 1) = 5;
  labels.at({2, 0}, 0, 2) = 9;
  std::vector<DisparityMap> disparity(3, DisparityMap(6, 1, 0.0f));
  disparity[2].at(0, 1) = 1.0f;
  // View 2 carries: 0->0, 5->2 (front), 9 lost, 5->3, 9->4, 9->5; pixel 1 gets nothing: one miss. Views 0 and 1
  // carry everything unchanged. 1 + 1/6.
  EXPECT_NEAR(KhanLabelsPerPixel(labels, disparity), 1.0 + 1.0 / 6.0, 1e-12);
}

TEST(KhanBoundaryRecall, UsesTheSobelBandOfBothMapsWithToleranceTwo) {
  const Labels gt = MakeLabels(3, 3, 12, 6, [](ViewIndex, int x, int) { return x < 4 ? 0 : 1; });
  EXPECT_DOUBLE_EQ(KhanBoundaryRecall(gt, gt), 1.0);
  // Our boundary between columns 6 and 7 (Sobel band: columns 6, 7); the truth's band is columns 3, 4. Column 4 is 2
  // from column 6 (recalled), column 3 is 3 away (missed): 0.5.
  const Labels shifted = MakeLabels(3, 3, 12, 6, [](ViewIndex, int x, int) { return x < 7 ? 0 : 1; });
  EXPECT_DOUBLE_EQ(KhanBoundaryRecall(shifted, gt), 0.5);
  const Labels none = MakeLabels(3, 3, 12, 6, [](ViewIndex, int, int) { return 3; });
  EXPECT_DOUBLE_EQ(KhanBoundaryRecall(none, gt), 0.0);
}

// Khan's boundary recall as his code computes it, with OpenCV: the Sobel gradient of each view's labels in doubles
// (replicated border), its non-zero pixels, the estimate's dilated by a 5 x 5 square; recall per view, averaged over
// the views with a boundary.
double KhanBoundaryRecallWithOpenCv(const Labels& labels, const Labels& gt) {
  const auto boundary = [](const cv::Mat& view) {
    cv::Mat values, gx, gy;
    view.convertTo(values, CV_64F);
    cv::Sobel(values, gx, CV_64F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
    cv::Sobel(values, gy, CV_64F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REPLICATE);
    return cv::Mat((gx != 0.0) | (gy != 0.0));
  };
  double sum = 0.0;
  int counted = 0;
  for (int cam = 0; cam < static_cast<int>(labels.shape().Views()); ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, labels.shape().nu);
    const cv::Mat truth = boundary(gt.View(view));
    if (cv::countNonZero(truth) == 0) continue;
    cv::Mat near, hit;
    cv::dilate(boundary(labels.View(view)), near, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
    cv::bitwise_and(truth, near, hit);
    sum += static_cast<double>(cv::countNonZero(hit)) / cv::countNonZero(truth);
    ++counted;
  }
  return sum / counted;
}

// KhanBoundaryRecall finds the same pixels in integers: on random blocks of labels 1, 2 and 3 (times a spread) with
// single-pixel specks among them (one pixel in 12), so that the Sobel sums of different labels around a pixel can
// cancel; the estimate's blocks and the truth's of different sizes and offsets, blocks cut by the border, and one view
// whose truth has no boundary at all.
TEST(KhanBoundaryRecall, MatchesTheSobelFormulationOnRandomBlocks) {
  std::mt19937 random(29);
  std::uniform_int_distribution<int> id(1, 3), size(2, 5), offset(0, 4), speck(0, 11);
  for (const int spread : {1, 7, 1000003}) {
    Labels labels(LightFieldShape{3, 3, 23, 17, 1}), gt(labels.shape());
    for (Labels* target : {&labels, &gt})
      for (int cam = 0; cam < 9; ++cam) {
        const ViewIndex view = ViewFromCameraNumber(cam, 3);
        const int block = size(random), shift_x = offset(random), shift_y = offset(random);
        std::vector<int> ids(16 * 16);  // one per block: at most (22 + 4) / 2 + 1 blocks along an axis
        for (int& value : ids) value = id(random) * spread;
        for (int y = 0; y < 17; ++y)
          for (int x = 0; x < 23; ++x) {
            const auto in_block = static_cast<std::size_t>((x + shift_x) / block * 16 + (y + shift_y) / block);
            target->at(view, y, x) = speck(random) == 0 ? id(random) * spread : ids[in_block];
          }
        if (cam == 4 && target == &gt) gt.View(view).setTo(5);
      }
    const double recall = KhanBoundaryRecall(labels, gt);
    EXPECT_GT(recall, 0.3);
    EXPECT_LT(recall, 1.0);
    EXPECT_EQ(recall, KhanBoundaryRecallWithOpenCv(labels, gt)) << "spread " << spread;
  }
}

TEST(KhanAchievableAccuracy, GivesEachSuperpixelOneObjectForTheWholeLightField) {
  // Two views of 4x4, one superpixel. View 0: all object 0 (overlap 16). View 1: 12 rays object 1, 4 rays object 0.
  // Khan: the superpixel is object 0 (its largest single-view overlap, 16): view 0 right 16/16, view 1 4/16: 0.625.
  // lfsp's ASA takes the best object per view: (16 + 12) / 32 = 0.875.
  const Labels labels = MakeLabels(2, 1, 4, 4, [](ViewIndex, int, int) { return 0; });
  const Labels gt = MakeLabels(2, 1, 4, 4, [](ViewIndex view, int, int y) { return view.u == 1 && y > 0 ? 1 : 0; });
  EXPECT_DOUBLE_EQ(KhanAchievableAccuracy(labels, gt), 0.625);
  EXPECT_DOUBLE_EQ(AchievableSegmentationAccuracy(labels, gt), 0.875);
}

TEST(KhanAverageSize, IsTheMeanSquareRootOfCentreAreas) {
  // Centre view (1, 1) of 3x3 views: labels of 4 and 16 rays (4x5 map: first row label 0, the rest label 1).
  const Labels labels = MakeLabels(3, 3, 4, 5, [](ViewIndex, int, int y) { return y == 0 ? 0 : 1; });
  EXPECT_DOUBLE_EQ(KhanAverageSize(labels), (2.0 + 4.0) / 2.0);
}

// Superpixel ids spread far apart (counted in ordered maps, not a table) give the same accuracy as dense ones, on
// random labels with ties and unknown objects (-1).
TEST(KhanAchievableAccuracy, SparseIdsScoreAsDenseOnes) {
  std::mt19937 random(17);
  std::uniform_int_distribution<int> superpixel(0, 11), object(-1, 3);
  Labels dense(LightFieldShape{3, 3, 16, 12, 1}), sparse(dense.shape()), gt(dense.shape());
  for (std::size_t i = 0; i < dense.size(); ++i) {
    dense.data()[i] = superpixel(random);
    sparse.data()[i] = dense.data()[i] * 100003;
    gt.data()[i] = object(random);
  }
  const double accuracy = KhanAchievableAccuracy(dense, gt);
  EXPECT_GT(accuracy, 0.0);
  EXPECT_LT(accuracy, 1.0);
  EXPECT_EQ(KhanAchievableAccuracy(sparse, gt), accuracy);
}

TEST(ScoreKhan, ReportsWhatTheInputsAllow) {
  const Labels labels = MakeLabels(3, 3, 8, 4, [](ViewIndex, int x, int) { return x / 4; });
  const auto disparity = ConstantDisparity(labels.shape(), 0.0f);
  const nlohmann::json both = ScoreKhan(labels, &labels, &disparity);
  for (const char* key : {"size", "self_similarity", "labels_per_pixel", "boundary_recall", "undersegmentation_error",
                          "achievable_accuracy"})
    EXPECT_TRUE(both.contains(key)) << key;
  EXPECT_DOUBLE_EQ(both["undersegmentation_error"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(both["achievable_accuracy"].get<double>(), 1.0);
  const nlohmann::json bare = ScoreKhan(labels, nullptr, nullptr);
  EXPECT_FALSE(bare.contains("self_similarity"));
  EXPECT_FALSE(bare.contains("boundary_recall"));
}

}  // namespace
}  // namespace lfsp::segment
