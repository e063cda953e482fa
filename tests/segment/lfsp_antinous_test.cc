// LFSP on the real HCI scene antinous (9x9 views of 512x512) with its ground-truth disparity. No label ground truth
// exists there, so the checks are the light-field properties: every label is one centre-view superpixel present in
// the centre view (ELR 1.0) and slices agree across views (self-similarity below 0.7 px, the target).

#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>

#include "lfsp/core/load.h"
#include "lfsp/core/pfm.h"
#include "lfsp/segment/lfsp.h"
#include "lfsp/segment/metrics.h"
#include "test_support.h"

namespace lfsp::segment {
namespace {

TEST(LfspAntinous, FullSlicedAndSelfSimilarWithGroundTruthDisparity) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const auto scene = data / "hci" / "antinous";
  const Bundle bundle = LoadLightField(scene);
  const DisparityMap gt = ReadPfm(scene / "gt_disp_lowres.pfm");
  LfspParams params;
  if (const char* json = std::getenv("LFSP_PARAMS")) params = ParamsFromJson(nlohmann::json::parse(json));
  const LfspResult result = SegmentLightField(bundle.light_field, gt, params);
  const std::vector<DisparityMap> view_disparity = PropagateDisparity(gt, result.labels.shape());
  const double ss = SelfSimilarity(result.labels, view_disparity);
  const double elr = EffectiveLabelRatio(result.labels);
  const double lpp = LabelsPerPixel(result.labels, gt, view_disparity);
  std::cout << "superpixels " << result.superpixels << " ss " << ss << " elr " << elr << " lpp " << lpp << " moves "
            << result.label_moves << " iterations " << result.iterations_run << "\n"
            << "time lab " << result.timings.lab_seconds << " initial " << result.timings.initial_seconds
            << " projection " << result.timings.projection_seconds << " refine " << result.timings.refine_seconds
            << " cleanup " << result.timings.cleanup_seconds << " total " << result.timings.total_seconds << "\n";
  EXPECT_EQ(elr, 1.0);
  EXPECT_LT(ss, 0.7);
  EXPECT_GT(result.superpixels, 500);  // 512^2 / 20^2 = 655 seeds
}

}  // namespace
}  // namespace lfsp::segment
