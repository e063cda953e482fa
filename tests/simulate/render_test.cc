// The ideal renderer agrees with its own ground truth: views warp onto the centre view with the ground-truth
// disparity, labels move with the disparity, occlusion is exact, and rendering is deterministic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/simulate/render.h"

namespace lfsp::simulate {
namespace {

float Bilinear(const LightField& lf, ViewIndex view, float x, float y, int c) {
  const int w = lf.shape().width, h = lf.shape().height;
  x = std::clamp(x, 0.0f, static_cast<float>(w - 1));
  y = std::clamp(y, 0.0f, static_cast<float>(h - 1));
  const int x0 = std::min(static_cast<int>(x), w - 2), y0 = std::min(static_cast<int>(y), h - 2);
  const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
  return lf.at(view, y0, x0, c) * (1 - fx) * (1 - fy) + lf.at(view, y0, x0 + 1, c) * fx * (1 - fy) +
         lf.at(view, y0 + 1, x0, c) * (1 - fx) * fy + lf.at(view, y0 + 1, x0 + 1, c) * fx * fy;
}

struct WarpError {
  double mean = 0;
  double p95 = 0;
  std::size_t samples = 0;
};

// Warps every view onto the centre with disparity (gt + bias) and compares colours, skipping pixels near label
// edges in the centre view and pixels whose ray is occluded in the other view (the view's ground-truth disparity
// at the landing point differs from the centre pixel's).
WarpError WarpToCentre(const RenderedLightField& r, float bias) {
  const auto& shape = r.light_field.shape();
  const ViewIndex centre = shape.Centre();
  std::vector<float> errors;
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      const ViewIndex view{u, v};
      if (view == centre) continue;
      const auto& view_disp = r.view_disparity[static_cast<std::size_t>(CameraNumber(view, shape.nu))];
      for (int y = 2; y < shape.height - 2; ++y)
        for (int x = 2; x < shape.width - 2; ++x) {
          const int label = r.labels.at(centre, y, x);
          bool interior = true;
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) interior &= r.labels.at(centre, y + dy, x + dx) == label;
          if (!interior) continue;
          const float d = r.disparity.at(y, x);
          const PixelPosition p = ProjectFromCentre({static_cast<float>(x), static_cast<float>(y)}, d, view, centre);
          const int px = static_cast<int>(std::lround(p.x)), py = static_cast<int>(std::lround(p.y));
          if (px < 1 || py < 1 || px >= shape.width - 1 || py >= shape.height - 1) continue;
          if (std::abs(view_disp.at(py, px) - d) > 0.05f) continue;  // occluded in this view
          const PixelPosition q =
              ProjectFromCentre({static_cast<float>(x), static_cast<float>(y)}, d + bias, view, centre);
          float e = 0;
          for (int c = 0; c < 3; ++c)
            e += std::abs(Bilinear(r.light_field, view, q.x, q.y, c) - r.light_field.at(centre, y, x, c));
          errors.push_back(e / 3.0f);
        }
    }
  WarpError out;
  out.samples = errors.size();
  if (errors.empty()) return out;
  double sum = 0;
  for (float e : errors) sum += e;
  out.mean = sum / static_cast<double>(errors.size());
  std::nth_element(errors.begin(), errors.begin() + static_cast<long>(errors.size() * 95 / 100), errors.end());
  out.p95 = errors[errors.size() * 95 / 100];
  return out;
}

TEST(Render, ViewsWarpToCentreWithGroundTruthDisparity) {
  RenderOptions options;
  options.nu = options.nv = 7;
  options.width = options.height = 128;
  for (const std::string name : {"planes", "spheres", "two-horses"}) {
    const RenderedLightField r = RenderLightField(BuiltinScene(name), options);
    const WarpError good = WarpToCentre(r, 0.0f);
    const WarpError wrong = WarpToCentre(r, 0.5f);
    SCOPED_TRACE(name);
    std::printf("%s: warp error mean %.4f p95 %.4f (n=%zu); with +0.5 px disparity bias mean %.4f\n", name.c_str(),
                good.mean, good.p95, good.samples, wrong.mean);
    ASSERT_GT(good.samples, 100000u);
    // The only residual is bilinear interpolation of anti-aliased texture (no noise): small on average, larger at
    // hard checker/stripe edges (planes: mean 0.011, p95 0.066 measured; smooth two-horses: mean 0.0004).
    EXPECT_LT(good.mean, 0.015) << "mean abs warp error";
    EXPECT_LT(good.p95, 0.1) << "95th percentile warp error";
    if (name == "two-horses") {
      EXPECT_LT(good.mean, 0.002);
    }
    // The check can fail: half a pixel per view step of disparity error must show clearly.
    EXPECT_GT(wrong.mean, 3.0 * good.mean);
  }
}

// Fronto-parallel planes at integer disparities: every centre ray lands exactly on a pixel centre of every view,
// so labels and disparities must move exactly, and wherever they do not the ray is occluded by something nearer.
TEST(Render, LabelsMoveWithDisparityAndNearestSurfaceWins) {
  const nlohmann::json json = {{"name", "integer-planes"},
                               {"objects",
                                {{{"name", "bg"},
                                  {"label", 0},
                                  {"disparity", -1},
                                  {"texture", {{"type", "noise"}, {"colours", {{0, 0, 0}, {1, 1, 1}}}}}},
                                 {{"name", "mid"},
                                  {"label", 1},
                                  {"disparity", 1},
                                  {"shape", {{"type", "rect"}, {"min", {0.2, 0.2}}, {"max", {0.7, 0.6}}}},
                                  {"texture", {{"type", "checker"}, {"colours", {{1, 0, 0}, {0, 0, 1}}}}}},
                                 {{"name", "near"},
                                  {"label", 7},
                                  {"disparity", 2},
                                  {"shape", {{"type", "disc"}, {"centre", {0.6, 0.55}}, {"radius", 0.15}}},
                                  {"texture", {{"type", "constant"}, {"colour", {0, 1, 0}}}}}}}};
  RenderOptions options;
  options.nu = options.nv = 5;
  options.width = 96;
  options.height = 80;
  const RenderedLightField r = RenderLightField(SceneFromJson(json), options);
  const auto& shape = r.light_field.shape();
  const ViewIndex centre = shape.Centre();
  std::size_t moved = 0, occluded = 0;
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u) {
      const ViewIndex view{u, v};
      const auto& vd = r.view_disparity[static_cast<std::size_t>(CameraNumber(view, shape.nu))];
      for (int y = 0; y < shape.height; ++y)
        for (int x = 0; x < shape.width; ++x) {
          const float d = r.disparity.at(y, x);
          ASSERT_EQ(d, std::round(d)) << "fronto-parallel integer planes have integer disparity";
          const int px = x - (u - centre.u) * static_cast<int>(d), py = y - (v - centre.v) * static_cast<int>(d);
          if (px < 0 || py < 0 || px >= shape.width || py >= shape.height) continue;
          if (r.labels.at(view, py, px) == r.labels.at(centre, y, x)) {
            ++moved;
            EXPECT_EQ(vd.at(py, px), d);
          } else {
            ++occluded;
            EXPECT_GT(vd.at(py, px), d) << "a label may only change where a nearer surface occludes";
          }
        }
    }
  EXPECT_GT(moved, 10 * occluded);
  EXPECT_GT(occluded, 100u);  // the scene does have occlusions
  // Exact occlusion in the centre view: the disc (d = 2) wins over the rect (d = 1) where both project.
  const int cx = static_cast<int>(0.6 * 96 - 0.5), cy = static_cast<int>(0.55 * 80 - 0.5);
  EXPECT_EQ(r.labels.at(centre, cy, cx), 7);
  EXPECT_EQ(r.labels.at(centre, static_cast<int>(0.25 * 80), static_cast<int>(0.25 * 96)), 1);
  EXPECT_EQ(r.labels.at(centre, 2, 2), 0);
}

TEST(Render, SlantedPlaneDisparityIsAnalytic) {
  const nlohmann::json json = {{"objects",
                                {{{"label", 0},
                                  {"disparity", 0.5},
                                  {"slope", {2.0, -1.0}},
                                  {"pivot", {0.5, 0.5}},
                                  {"texture", {{"type", "gradient"}, {"colours", {{0, 0, 0}, {1, 1, 1}}}}}}}}};
  RenderOptions options;
  options.nu = options.nv = 3;
  options.width = 64;
  options.height = 32;
  const RenderedLightField r = RenderLightField(SceneFromJson(json), options);
  for (int y = 0; y < 32; y += 5)
    for (int x = 0; x < 64; x += 7) {
      const double xn = (x + 0.5) / 64.0, yn = (y + 0.5) / 32.0;
      EXPECT_NEAR(r.disparity.at(y, x), 0.5 + 2.0 * (xn - 0.5) - 1.0 * (yn - 0.5), 1e-4);
      // In a side view the same ray meets the plane at X = px + s d with d affine in X: check self-consistency.
      const float d = r.view_disparity[0].at(y, x);  // view (0, 0): s = t = -1
      const double X = (x - d + 0.5) / 64.0, Y = (y - d + 0.5) / 32.0;
      EXPECT_NEAR(d, 0.5 + 2.0 * (X - 0.5) - 1.0 * (Y - 0.5), 1e-4);
    }
}

TEST(Render, DeterministicAndCentreDisparityMatchesViewDisparity) {
  RenderOptions options;
  options.nu = options.nv = 5;
  options.width = options.height = 64;
  const Scene scene = BuiltinScene("occluders");
  const RenderedLightField a = RenderLightField(scene, options);
  const RenderedLightField b = RenderLightField(scene, options);
  ASSERT_EQ(a.light_field.size(), b.light_field.size());
  EXPECT_EQ(0, std::memcmp(a.light_field.data(), b.light_field.data(), a.light_field.size() * sizeof(float)));
  EXPECT_EQ(0, std::memcmp(a.labels.data(), b.labels.data(), a.labels.size() * sizeof(std::int32_t)));
  const auto& centre = a.view_disparity[12];
  EXPECT_EQ(0, std::memcmp(centre.data(), a.disparity.data(), 64 * 64 * sizeof(float)));
  // Every label of the scene that is visible somewhere is a scene label.
  for (std::size_t i = 0; i < a.labels.size(); ++i) ASSERT_TRUE(a.labels.data()[i] >= 0 && a.labels.data()[i] <= 5);
}

TEST(Render, RejectsBadOptions) {
  RenderOptions options;
  options.width = 0;
  EXPECT_THROW(RenderLightField(BuiltinScene("planes"), options), Error);
  options.width = 16;
  options.supersampling = 0;
  EXPECT_THROW(RenderLightField(BuiltinScene("planes"), options), Error);
}

}  // namespace
}  // namespace lfsp::simulate
