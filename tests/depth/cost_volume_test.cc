// BuildCostVolume's two ways of treating pixels near an edge: merged (the cheapest of the whole angular patch and
// its partial patches, in one volume) or handed out (the whole patch's volume, the partial patches' apart, for
// EstimateDepth's thin-structure check). Both must come from the same arithmetic: the merged volume is the
// element-wise minimum of the three handed out, and the whole patch near an edge is the plain all-views cost.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "lfsp/depth/cost_volume.h"
#include "lfsp/depth/occlusion.h"
#include "synthetic_light_field.h"

namespace lfsp::depth {
namespace {

struct Volumes {
  CostVolume merged, whole, all_views;
  OcclusionAlternatives alternatives;
};

Volumes Build(const LightField& light_field, const std::vector<float>& disparities, const CostOptions& options,
              const OcclusionMap& occlusion) {
  Volumes volumes;
  volumes.merged = BuildCostVolume(light_field, disparities, options, &occlusion);
  volumes.whole = BuildCostVolume(light_field, disparities, options, &occlusion, &volumes.alternatives);
  volumes.all_views = BuildCostVolume(light_field, disparities, options, nullptr);
  return volumes;
}

TEST(CostVolume, HandedOutPartialPatchesAreTheOnesItWouldMerge) {
  testing::ShiftScene scene;
  scene.size = 64;
  const testing::ShiftLightField made = testing::MakeShiftLightField(scene);
  const LightField& light_field = made.light_field;
  const std::vector<float> disparities = LabelDisparities(-1.5f, 1.7f, 24);
  OcclusionOptions occlusion_options;
  occlusion_options.radius = 6.0;
  const OcclusionMap occlusion =
      DetectOcclusionEdges(light_field.View(light_field.shape().Centre()), occlusion_options);
  ASSERT_GT(occlusion.Candidates(), 200);

  for (const Sampler sampler : {Sampler::kBilinear, Sampler::kNoiseMatched}) {
    CostOptions options;
    options.sampler = sampler;
    options.half_patch_penalty = 1.1f;  // both penalties in play, so each path must apply them alike
    const Volumes volumes = Build(light_field, disparities, options, occlusion);
    int half_wins = 0, along_wins = 0;
    for (int y = 0; y < volumes.whole.height(); ++y)
      for (int x = 0; x < volumes.whole.width(); ++x) {
        const bool candidate = occlusion.candidate.at<unsigned char>(y, x) != 0;
        const float* merged = volumes.merged.Curve(y, x);
        const float* whole = volumes.whole.Curve(y, x);
        const float* half = volumes.alternatives.half.Curve(y, x);
        const float* along = volumes.alternatives.along.Curve(y, x);
        const float* all_views = volumes.all_views.Curve(y, x);
        for (std::size_t l = 0; l < disparities.size(); ++l) {
          ASSERT_EQ(merged[l], std::min({whole[l], half[l], along[l]}))
              << SamplerName(sampler) << " at (" << x << ", " << y << "), label " << l;
          ASSERT_NEAR(whole[l], all_views[l], 1e-5f * (1.0f + all_views[l]))
              << SamplerName(sampler) << " at (" << x << ", " << y << "), label " << l;
          if (!candidate) {
            ASSERT_TRUE(std::isinf(half[l]) && std::isinf(along[l])) << "(" << x << ", " << y << ") is no candidate";
          }
          half_wins += half[l] < std::min(whole[l], along[l]);
          along_wins += along[l] < std::min(whole[l], half[l]);
        }
      }
    // The comparison means something only if each partial patch is the cheapest somewhere.
    EXPECT_GT(half_wins, 100) << SamplerName(sampler);
    EXPECT_GT(along_wins, 100) << SamplerName(sampler);
  }
}

}  // namespace
}  // namespace lfsp::depth
