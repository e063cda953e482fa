// LoadCentralViews (issue 46): an .h5 bundle read only for the views a stage keeps gives the same light field,
// weights, labels, disparity and choice as loading all of it and cropping, in every sample storage; other formats are
// loaded whole and cropped alike.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "lfsp/core/error.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/load.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/core/views_folder.h"
#include "test_support.h"

namespace lfsp {
namespace {

using lfsp::testing::TempDir;

// 9x9 views whose weights fall ring by ring (1.0, 0.9, 0.7, 0.45, 0.2, with a little per-pixel spread, so the means
// are not round), samples that differ everywhere, labels, and a disparity map.
Bundle RingWeightedBundle() {
  Bundle bundle;
  LightField& light_field = bundle.light_field;
  light_field = LightField(LightFieldShape{9, 9, 6, 5, 3});
  for (std::size_t i = 0; i < light_field.size(); ++i)
    light_field.data()[i] = static_cast<float>((i * 7919) % 1000) / 1000.0f;
  light_field.EnableWeights();
  const float ring_weight[5] = {1.0f, 0.9f, 0.7f, 0.45f, 0.2f};
  for (int v = 0; v < 9; ++v)
    for (int u = 0; u < 9; ++u) {
      float* w = light_field.weights().ViewData({u, v});
      for (int k = 0; k < 30; ++k)
        w[k] = ring_weight[std::max(std::abs(u - 4), std::abs(v - 4))] - 0.001f * static_cast<float>(k % 7);
    }
  light_field.transfer = Transfer::kLinear;
  Labels labels(LightFieldShape{9, 9, 6, 5, 1});
  for (std::size_t i = 0; i < labels.size(); ++i) labels.data()[i] = static_cast<std::int32_t>(i % 37);
  bundle.labels = std::move(labels);
  DisparityMap disparity(6, 5);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 6; ++x) disparity.at(y, x) = 0.1f * static_cast<float>(x - y);
  bundle.disparity = std::move(disparity);
  return bundle;
}

void ExpectSameArrays(const float* a, const float* b, std::size_t count) {
  EXPECT_EQ(std::memcmp(a, b, count * sizeof(float)), 0);
}

void ExpectLoadsAsCropped(const std::filesystem::path& path, int requested) {
  SCOPED_TRACE(path.string() + ", requested " + std::to_string(requested));
  Bundle whole = LoadLightField(path);
  const ViewChoice expected = ChooseViews(whole.light_field, requested);
  KeepCentralViews(whole.light_field, whole.labels, expected.n);
  const LoadedViews loaded = LoadCentralViews(path, requested);
  EXPECT_EQ(loaded.choice.n, expected.n);
  EXPECT_EQ(loaded.choice.available, expected.available);
  EXPECT_EQ(loaded.choice.least_weight, expected.least_weight);
  EXPECT_EQ(loaded.choice.reason, expected.reason);
  const LightField& light_field = loaded.bundle.light_field;
  ASSERT_EQ(light_field.shape(), whole.light_field.shape());
  EXPECT_EQ(light_field.transfer, whole.light_field.transfer);
  ExpectSameArrays(light_field.data(), whole.light_field.data(), light_field.size());
  ASSERT_EQ(light_field.HasWeights(), whole.light_field.HasWeights());
  if (light_field.HasWeights())
    ExpectSameArrays(light_field.weights().data(), whole.light_field.weights().data(), light_field.weights().size());
  ASSERT_EQ(loaded.bundle.labels.has_value(), whole.labels.has_value());
  if (whole.labels) {
    ASSERT_EQ(loaded.bundle.labels->shape(), whole.labels->shape());
    EXPECT_TRUE(
        std::equal(whole.labels->data(), whole.labels->data() + whole.labels->size(), loaded.bundle.labels->data()));
  }
  ASSERT_EQ(loaded.bundle.disparity.has_value(), whole.disparity.has_value());
  if (whole.disparity)
    ExpectSameArrays(loaded.bundle.disparity->data(), whole.disparity->data(),
                     static_cast<std::size_t>(whole.disparity->width() * whole.disparity->height()));
}

TEST(LoadCentralViews, BundlesReadOnlyTheKeptViewsAsLoadingAllAndCropping) {
  TempDir temp;
  const Bundle bundle = RingWeightedBundle();
  for (const SampleStorage storage : {SampleStorage::kUint16, SampleStorage::kFloat32}) {
    for (const int level : {1, 0}) {
      const std::filesystem::path path =
          temp / ("b" + std::to_string(static_cast<int>(storage)) + std::to_string(level) + ".h5");
      WriteBundle(bundle, path, {storage, level});
      for (const int requested : {0, 3, 9}) ExpectLoadsAsCropped(path, requested);
      EXPECT_EQ(LoadCentralViews(path, 0).choice.n, 7);  // ring 3 (0.45) kept, ring 4 (0.2) not
      EXPECT_THROW(LoadCentralViews(path, 4), Error);
    }
  }
}

TEST(LoadCentralViews, ViewMeanWeightsOfABundleAreTheLightFieldsOwn) {
  TempDir temp;
  const Bundle bundle = RingWeightedBundle();
  WriteBundle(bundle, temp / "b.h5", {SampleStorage::kFloat32, 1});
  const std::vector<double> means = ReadViewMeanWeights(temp / "b.h5");
  ASSERT_EQ(means.size(), 81u);
  for (int v = 0; v < 9; ++v)
    for (int u = 0; u < 9; ++u)
      EXPECT_EQ(means[static_cast<std::size_t>(v * 9 + u)], MeanViewWeight(bundle.light_field, {u, v}));

  Bundle unweighted;
  unweighted.light_field = LightField(LightFieldShape{5, 5, 4, 3, 3});
  WriteBundle(unweighted, temp / "plain.h5", {SampleStorage::kFloat32, 1});
  EXPECT_TRUE(ReadViewMeanWeights(temp / "plain.h5").empty());
  EXPECT_EQ(LoadCentralViews(temp / "plain.h5", 0).choice.n, 5) << "without weights every view is kept";
}

TEST(LoadCentralViews, OtherFormatsAreLoadedWholeAndCropped) {
  TempDir temp;
  Bundle bundle = RingWeightedBundle();
  bundle.labels.reset();
  WriteViewsFolder(bundle.light_field, temp / "views");
  ExpectLoadsAsCropped(temp / "views", 0);
  ExpectLoadsAsCropped(temp / "views", 5);
}

}  // namespace
}  // namespace lfsp
