// Central views: the kept views are exactly the middle ones, with their weights, and impossible crops are refused.

#include "lfsp/core/view_crop.h"

#include <gtest/gtest.h>

#include "lfsp/core/error.h"

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

}  // namespace
}  // namespace lfsp
