// Central views: the kept views are exactly the middle ones, with their weights, and impossible crops are refused.

#include "lfsp/core/view_crop.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/registration.h"

namespace lfsp {
namespace {

LightField Numbered(int views) {
  LightField light_field(LightFieldShape{views, views, 4, 3, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i) light_field.data()[i] = static_cast<float>(i);
  light_field.EnableWeights(0.0f);
  for (std::size_t i = 0; i < light_field.weights().size(); ++i)
    light_field.weights().data()[i] = -static_cast<float>(i);
  light_field.transfer = Transfer::kLinear;
  return light_field;
}

TEST(CentralViews, KeepsTheMiddleViewsWithTheirWeights) {
  const LightField full = Numbered(5);
  const LightField cropped = CentralViews(full, 3);
  ASSERT_EQ(cropped.shape(), (LightFieldShape{3, 3, 4, 3, 3}));
  EXPECT_EQ(cropped.transfer, Transfer::kLinear);
  ASSERT_TRUE(cropped.HasWeights());
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
          EXPECT_EQ(cropped.at({u, v}, y, x, 2), full.at({u + 1, v + 1}, y, x, 2));
          EXPECT_EQ(cropped.weights().at({u, v}, y, x), full.weights().at({u + 1, v + 1}, y, x));
        }
  EXPECT_EQ(cropped.at(cropped.shape().Centre(), 1, 1), full.at(full.shape().Centre(), 1, 1));
}

TEST(CentralViews, CropsLabelsTheSameWay) {
  Labels labels(LightFieldShape{5, 5, 2, 2, 1});
  for (std::size_t i = 0; i < labels.size(); ++i) labels.data()[i] = static_cast<std::int32_t>(i);
  const Labels cropped = CentralViews(labels, 1);
  ASSERT_EQ(cropped.shape().Views(), 1u);
  EXPECT_EQ(cropped.at({0, 0}, 1, 0), labels.at({2, 2}, 1, 0));
}

TEST(CentralViews, RefusesCropsWithoutACommonCentre) {
  const LightField full = Numbered(5);
  EXPECT_THROW(CentralViews(full, 4), Error);
  EXPECT_THROW(CentralViews(full, 7), Error);
  EXPECT_THROW(CentralViews(full, 0), Error);
  EXPECT_NO_THROW(CentralViews(full, 5));
}

// Where the central views lie (the pipeline reads only those of the simulator's labels): the block CentralViews
// copies, with the same checks.
TEST(CentralViewBlock, IsTheBlockCentralViewsCopies) {
  const LightField full = Numbered(5);
  const ViewBlock block = CentralViewBlock(full.shape(), 3);
  EXPECT_EQ(block.first, (ViewIndex{1, 1}));
  EXPECT_EQ(block.nu, 3);
  EXPECT_EQ(block.nv, 3);
  const LightField cropped = CentralViews(full, 3);
  EXPECT_EQ(cropped.View({0, 0}).at<cv::Vec3f>(0, 0), full.View(block.first).at<cv::Vec3f>(0, 0));
  EXPECT_THROW(CentralViewBlock(full.shape(), 4), Error);
}

// A 9x9 light field whose views' weight falls with their Chebyshev ring from the centre: 1.0, 0.9, 0.7, 0.45, 0.2.
LightField RingWeighted() {
  LightField light_field(LightFieldShape{9, 9, 4, 4, 3});
  light_field.EnableWeights();
  const float ring_weight[5] = {1.0f, 0.9f, 0.7f, 0.45f, 0.2f};
  for (int v = 0; v < 9; ++v)
    for (int u = 0; u < 9; ++u) {
      float* w = light_field.weights().ViewData({u, v});
      std::fill(w, w + 16, ring_weight[std::max(std::abs(u - 4), std::abs(v - 4))]);
    }
  return light_field;
}

TEST(ChooseViews, KeepsTheLargestSquareWhoseViewsAreAllWellLit) {
  const LightField light_field = RingWeighted();
  const ViewChoice automatic = ChooseViews(light_field);
  EXPECT_EQ(automatic.n, 7);  // ring 3 (0.45) is kept, ring 4 (0.2) is not
  EXPECT_EQ(automatic.available, 9);
  EXPECT_FLOAT_EQ(automatic.least_weight, 0.45);
  const ViewChoice requested = ChooseViews(light_field, 3);
  EXPECT_EQ(requested.n, 3);
  EXPECT_FLOAT_EQ(requested.least_weight, 0.9);
  EXPECT_THROW(ChooseViews(light_field, 4), Error);
  EXPECT_EQ(ChooseViews(LightField(LightFieldShape{5, 5, 4, 3, 3})).n, 5) << "without weights every view is kept";
}

TEST(WellLitCentralSize, AppliesChooseViewsRuleToAnySourceOfMeans) {
  const LightFieldShape shape{9, 9, 4, 4, 3};
  std::vector<int> asked_rings;
  const auto ring_mean = [&](ViewIndex view) {
    const int ring = std::max(std::abs(view.u - 4), std::abs(view.v - 4));
    asked_rings.push_back(ring);
    const double mean[5] = {1.0, 0.9, 0.7, 0.45, 0.2};
    return mean[ring];
  };
  EXPECT_EQ(WellLitCentralSize(shape, ring_mean), 7);
  EXPECT_EQ(*std::max_element(asked_rings.begin(), asked_rings.end()), 4) << "no ring beyond the first dim one";
  EXPECT_EQ(WellLitCentralSize(shape, ring_mean, 0.5), 5) << "a higher threshold stops at ring 2";
  EXPECT_EQ(WellLitCentralSize(shape, ring_mean, 0.1), 9);
  EXPECT_EQ(WellLitCentralSize(LightFieldShape{8, 8, 4, 4, 3}, [](ViewIndex) { return 0.0; }), 2)
      << "an even grid keeps its central 2x2 at least";
}

TEST(CentralShape, IsTheShapeCentralViewsGives) {
  const LightFieldShape shape{15, 15, 4, 3, 3};
  EXPECT_EQ(CentralShape(shape, 9).nu, 9);
  EXPECT_EQ(CentralShape(shape, 9).width, 4);
  EXPECT_THROW(CentralShape(shape, 8), Error);
  EXPECT_THROW(CentralShape(shape, 17), Error);
}

TEST(KeepCentralViews, CropsLightFieldAndLabelsInPlace) {
  LightField light_field = RingWeighted();
  std::optional<Labels> labels = Labels(light_field.shape(), 3);
  KeepCentralViews(light_field, labels, 5);
  EXPECT_EQ(light_field.shape().nu, 5);
  EXPECT_EQ(labels->shape().nu, 5);
  EXPECT_FLOAT_EQ(MeanViewWeight(light_field, {0, 0}), 0.7);  // was ring 2
}

TEST(MeasureShift, RecoversASubPixelTranslation) {
  cv::Mat reference(64, 64, CV_32F), moving(64, 64, CV_32F);
  auto pattern = [](double x, double y) {
    return static_cast<float>(0.5 + 0.2 * std::sin(0.3 * x) * std::cos(0.23 * y));
  };
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      reference.at<float>(y, x) = pattern(x, y);
      moving.at<float>(y, x) = 1.1f * pattern(x - 0.12, y + 0.07) + 0.02f;  // shifted, with a gain and an offset
    }
  const Shift2D shift = MeasureShift(reference, moving, 4);
  EXPECT_NEAR(shift.dx, 0.12, 0.01);
  EXPECT_NEAR(shift.dy, -0.07, 0.01);
}

// Only the mask's pixels count: the right half, moved by another amount, does not pull the left half's shift.
TEST(MeasureShift, KeepsToTheMask) {
  cv::Mat reference(64, 64, CV_32F), moving(64, 64, CV_32F), mask(64, 64, CV_8U, cv::Scalar(0));
  auto pattern = [](double x, double y) {
    return static_cast<float>(0.5 + 0.2 * std::sin(0.3 * x) * std::cos(0.23 * y));
  };
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      reference.at<float>(y, x) = pattern(x, y);
      moving.at<float>(y, x) = pattern(x - (x < 32 ? 0.1 : 0.6), y);
      if (x < 28) mask.at<unsigned char>(y, x) = 255;
    }
  EXPECT_NEAR(MeasureShift(reference, moving, 4, mask).dx, 0.1, 0.01);
  EXPECT_GT(MeasureShift(reference, moving, 4).dx, 0.2);  // without the mask the two halves mix
  EXPECT_THROW(MeasureShift(reference, moving, 4, cv::Mat(32, 32, CV_8U, cv::Scalar(255))), Error);
}

// An sRGB-encoded decode registers against a linear truth in linear light: the curve moves a blurred step edge's
// steepest point towards its dark side, which compared as it is reads as a shift.
TEST(RegisterViews, ComparesInLinearLight) {
  LightField truth(LightFieldShape{3, 3, 64, 64, 3});
  truth.transfer = Transfer::kLinear;
  truth.EnableWeights();
  LightField decoded(truth.shape());
  decoded.transfer = Transfer::kSrgb;
  auto linear = [](double x, double y) {
    return static_cast<float>(0.02 + 0.6 / (1.0 + std::exp(-(x - 32.0) / 2.0)) + 0.01 * std::sin(0.5 * y));
  };
  for (int v = 0; v < 3; ++v)
    for (int u = 0; u < 3; ++u)
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          for (int c = 0; c < 3; ++c) {
            truth.View({u, v}).at<cv::Vec3f>(y, x)[c] = linear(x, y);
            decoded.View({u, v}).at<cv::Vec3f>(y, x)[c] = LinearToSrgb(linear(x, y));
          }
  const ViewRegistration registration = RegisterViews(decoded, truth, 0.5, 4);
  EXPECT_EQ(registration.registered, 9);
  EXPECT_LT(registration.worst, 0.005);
  // Compared as encoded, the same views read far off.
  const Shift2D encoded = MeasureShift(GreyOf(truth.View({1, 1})), GreyOf(decoded.View({1, 1})), 4);
  EXPECT_GT(std::abs(encoded.dx), 0.1);
}

// Every well-lit view registered; a decode displaced by a known amount in one view reads that amount there.
TEST(RegisterViews, MeasuresEachWellLitViewAndSkipsTheDimOnes) {
  LightField truth(LightFieldShape{5, 5, 64, 64, 3});
  truth.EnableWeights();
  LightField decoded(truth.shape());
  auto pattern = [](double x, double y) {
    return static_cast<float>(0.5 + 0.2 * std::sin(0.3 * x) * std::cos(0.23 * y));
  };
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 5; ++u) {
      const ViewIndex view{u, v};
      const double shift = (u == 3 && v == 2) ? 0.1 : 0.0;
      float* w = truth.weights().ViewData(view);
      std::fill(w, w + 64 * 64, std::max(std::abs(u - 2), std::abs(v - 2)) == 2 ? 0.3f : 0.9f);
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          for (int c = 0; c < 3; ++c) {
            truth.View(view).at<cv::Vec3f>(y, x)[c] = pattern(x, y);
            decoded.View(view).at<cv::Vec3f>(y, x)[c] = 0.7f * pattern(x - shift, y);
          }
    }
  const ViewRegistration registration = RegisterViews(decoded, truth, 0.5, 4);
  EXPECT_EQ(registration.registered, 9);  // the inner 3x3; the outer ring is dim
  EXPECT_NEAR(registration.worst, 0.1, 0.01);
  for (const ViewShift& entry : registration.views) {
    EXPECT_EQ(entry.registered, entry.weight > 0.5);
    if (entry.registered && !(entry.view.u == 3 && entry.view.v == 2)) {
      EXPECT_NEAR(entry.shift.dx, 0.0, 1e-3);
    }
  }
  EXPECT_THROW(RegisterViews(decoded, LightField(LightFieldShape{3, 3, 64, 64, 3}), 0.5, 4), Error);
}

// The ideal light field a row of views at a time (what the pipeline reads of the simulator's truth) gives exactly
// RegisterViews's figures.
TEST(RegisterViews, RowByRowGivesTheSameFigures) {
  LightField truth(LightFieldShape{5, 5, 64, 64, 3});
  truth.EnableWeights();
  LightField decoded(truth.shape());
  for (int v = 0; v < 5; ++v)
    for (int u = 0; u < 5; ++u) {
      const ViewIndex view{u, v};
      const double shift = 0.02 * (u - 2) - 0.03 * (v - 2);
      float* w = truth.weights().ViewData(view);
      std::fill(w, w + 64 * 64, 0.2f + 0.1f * static_cast<float>(4 - std::abs(u - 2) - std::abs(v - 2)));
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
          for (int c = 0; c < 3; ++c) {
            truth.View(view).at<cv::Vec3f>(y, x)[c] =
                static_cast<float>(0.5 + 0.2 * std::sin(0.3 * x + c) * std::cos(0.23 * y));
            decoded.View(view).at<cv::Vec3f>(y, x)[c] =
                static_cast<float>(0.5 + 0.2 * std::sin(0.3 * (x - shift) + c) * std::cos(0.23 * y));
          }
    }
  const ViewRegistration whole = RegisterViews(decoded, truth, 0.5, 4);
  ViewRegistration rows;
  rows.views.resize(truth.shape().Views());
  for (int v = 0; v < 5; ++v) {
    LightField row(LightFieldShape{5, 1, 64, 64, 3});
    row.EnableWeights();
    for (int u = 0; u < 5; ++u) {
      truth.View({u, v}).copyTo(row.View({u, 0}));
      const float* w = truth.weights().ViewData({u, v});
      std::copy(w, w + 64 * 64, row.weights().ViewData({u, 0}));
    }
    RegisterBlock(decoded, row, ViewIndex{0, v}, 0.5, 4, cv::Mat(), rows);
  }
  CountRegistered(rows);
  EXPECT_GT(whole.registered, 0);
  EXPECT_LT(whole.registered, 25);
  EXPECT_EQ(rows.registered, whole.registered);
  EXPECT_EQ(rows.worst, whole.worst);
  for (std::size_t i = 0; i < whole.views.size(); ++i) {
    EXPECT_EQ(rows.views[i].view, whole.views[i].view);
    EXPECT_EQ(rows.views[i].weight, whole.views[i].weight);
    EXPECT_EQ(rows.views[i].registered, whole.views[i].registered);
    EXPECT_EQ(rows.views[i].shift.dx, whole.views[i].shift.dx);
    EXPECT_EQ(rows.views[i].shift.dy, whole.views[i].shift.dy);
  }
  // A block that does not lie inside the decoded light field is refused.
  EXPECT_THROW(
      RegisterBlock(decoded, LightField(LightFieldShape{5, 1, 64, 64, 3}), ViewIndex{1, 0}, 0.5, 4, cv::Mat(), rows),
      Error);
}

}  // namespace
}  // namespace lfsp
