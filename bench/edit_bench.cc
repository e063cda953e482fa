// Edit stage: recolouring an antinous-size light field through superpixel labels, and refocusing (focal stack of
// 8 slices, all-in-focus, shear) on the HCI scene antinous (issue 8).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "bench_case.h"
#include "lfsp/core/load.h"
#include "lfsp/core/shear.h"
#include "lfsp/edit/image_measures.h"
#include "lfsp/edit/recolor.h"
#include "lfsp/edit/refocus.h"
#include "lfsp/edit/selection.h"

namespace lfsp::bench {
namespace {

std::filesystem::path Antinous() { return std::filesystem::path(SharedDataDir()) / "hci" / "antinous"; }

// Kept alive across runs of a case (each case runs in its own process).
Bundle& Loaded() {
  static Bundle bundle;
  return bundle;
}
Labels& SyntheticLabels() {
  static Labels labels;
  return labels;
}

std::string Format(const char* format, double value) {
  char text[96];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

// Superpixel-like labels consistent across views: 16x16-pixel cells of the centre view, split by disparity into
// layers of 0.5 px/view, followed into every view along the ground-truth disparity of the centre pixel (a stand-in
// for `lfsp segment` output with the same count and sizes of labels: about 1000 per view).
Labels MakeSyntheticLabels(const Bundle& bundle) {
  const LightFieldShape& shape = bundle.light_field.shape();
  Labels labels(shape);
  const DisparityMap& disparity = *bundle.disparity;
  const ViewIndex centre = shape.Centre();
  for (int v = 0; v < shape.nv; ++v)
    for (int u = 0; u < shape.nu; ++u)
      for (int y = 0; y < shape.height; ++y)
        for (int x = 0; x < shape.width; ++x) {
          const float d = disparity.at(y, x);  // approximation: the centre pixel's disparity at the same position
          const float cx = static_cast<float>(x) + static_cast<float>(u - centre.u) * d;
          const float cy = static_cast<float>(y) + static_cast<float>(v - centre.v) * d;
          const int gx = std::clamp(static_cast<int>(cx) / 16, 0, 31);
          const int gy = std::clamp(static_cast<int>(cy) / 16, 0, 31);
          const int layer = std::clamp(static_cast<int>(std::floor((d + 4.0f) * 2.0f)), 0, 15);
          labels.at({u, v}, y, x) = (layer * 32 + gy) * 32 + gx;
        }
  return labels;
}

void PrepareAntinous() {
  Loaded() = LoadLightField(Antinous());
  if (!Loaded().disparity) throw std::runtime_error("antinous: no ground-truth disparity");
}

}  // namespace

// Recolour the bust: every superpixel with more than half its centre-view area inside the central 256x320 box,
// hue +40 degrees, saturation x1.3, feathered over 2 px, in all 81 views. In place (repeated runs keep editing).
LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "edit";
  c.name = "recolor-feather2";
  c.input = "antinous 9x9x512x512, ~1000 synthetic labels/view";
  c.target = "-";
  c.needs_shared_data = true;
  c.prepare = [] {
    PrepareAntinous();
    SyntheticLabels() = MakeSyntheticLabels(Loaded());
  };
  c.run = [] {
    cv::Mat mask(512, 512, CV_8UC1, cv::Scalar(0));
    mask(cv::Rect(128, 96, 256, 320)).setTo(255);
    const std::vector<std::int32_t> selection = edit::SelectByMask(SyntheticLabels(), mask);
    edit::RecolorOptions options;
    options.adjustment.hue_degrees = 40.0f;
    options.adjustment.saturation = 1.3f;
    options.feather_px = 2.0f;
    const edit::RecolorStats stats = edit::Recolor(Loaded().light_field, SyntheticLabels(), selection, options);
    const double total = static_cast<double>(Loaded().light_field.size() / 3);
    return Format("edited %.1f%% of rays",
                  100.0 * static_cast<double>(stats.selected_rays + stats.feather_rays) / total);
  };
  return c;
}

// A focal stack of 8 slices over the scene's disparity range. Quality: mean PSNR against the centre view over the
// pixels whose ground-truth disparity is within 0.05 of the slice's (sharp where in focus).
LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "edit";
  c.name = "focal-stack-8";
  c.input = "antinous 9x9x512x512";
  c.target = "-";
  c.needs_shared_data = true;
  c.prepare = PrepareAntinous;
  c.run = [] {
    const LightField& light_field = Loaded().light_field;
    const std::vector<float> disparities = edit::EvenlySpacedDisparities(-3.3f, 2.8f, 8);
    const std::vector<cv::Mat> stack = edit::FocalStack(light_field, disparities);
    const cv::Mat centre = light_field.View(light_field.shape().Centre());
    double psnr_sum = 0.0;
    int counted = 0;
    for (std::size_t i = 0; i < stack.size(); ++i) {
      const cv::Mat in_focus = cv::abs(Loaded().disparity->Mat() - disparities[i]) < 0.05f;
      if (cv::countNonZero(in_focus) < 100) continue;
      psnr_sum += edit::Psnr(centre, stack[i], in_focus);
      ++counted;
    }
    return Format("in-focus PSNR %.1f dB", counted == 0 ? 0.0 : psnr_sum / counted);
  };
  return c;
}

// All-in-focus from the ground-truth disparity; quality: PSNR against the centre view.
LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "edit";
  c.name = "all-in-focus";
  c.input = "antinous 9x9x512x512 + GT disparity";
  c.target = "-";
  c.needs_shared_data = true;
  c.prepare = PrepareAntinous;
  c.run = [] {
    const LightField& light_field = Loaded().light_field;
    const cv::Mat sharp = edit::AllInFocus(light_field, *Loaded().disparity);
    return Format("PSNR vs centre %.1f dB", edit::Psnr(light_field.View(light_field.shape().Centre()), sharp));
  };
  return c;
}

// The sheared light field at one refocus level (the segment stage's refocus sweep does this 7 times).
LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "edit";
  c.name = "shear-light-field";
  c.input = "antinous 9x9x512x512";
  c.target = "-";
  c.needs_shared_data = true;
  c.prepare = PrepareAntinous;
  c.run = [] {
    const LightField sheared = ShearLightField(Loaded().light_field, 1.0f);
    return std::string();
  };
  return c;
}

}  // namespace lfsp::bench
