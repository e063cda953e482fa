#include "lab_image.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/error.h"
#include "lfsp/core/srgb.h"

namespace lfsp::segment {
namespace {

float EncodeSrgb(float linear) { return LinearToSrgb(std::clamp(linear, 0.0f, 1.0f)); }

}  // namespace

cv::Mat LabView(LabRays& lab, const LightFieldShape& shape, ViewIndex view) {
  const std::size_t offset =
      (static_cast<std::size_t>(view.v) * static_cast<std::size_t>(shape.nu) + static_cast<std::size_t>(view.u)) *
      shape.ViewPixels() * 3;
  return cv::Mat(shape.height, shape.width, CV_32FC3, lab.data() + offset);
}

void SmoothLabViews(LabRays& lab, const LightFieldShape& shape, double sigma) {
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    cv::Mat view = LabView(lab, shape, ViewFromCameraNumber(cam, shape.nu));
    cv::GaussianBlur(view, view, cv::Size(0, 0), sigma, sigma, cv::BORDER_REFLECT);
  }
}

LabRays LabOfLightField(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  if (shape.channels != 3 && shape.channels != 1) {
    throw Error("segmentation needs an RGB or grey light field, got " + std::to_string(shape.channels) + " channels");
  }
  // Not zero-filled: the loop below writes every sample, each thread its own contiguous run of views. On antinous
  // the allocation with its serial zero fill took 90 ms, and the whole step went 0.216 -> 0.170 s without it (the
  // page faults remain, now in parallel). The schedule is static on purpose: a dynamic one, interleaving the views
  // between the threads, made the refinement that later reads them slower on this machine on every 2-thread run
  // (1.5 -> 2.2 s; with one thread no change). The cause was not found (BENCHMARKS.md, twenty-sixth session).
  LabRays lab(shape.Views() * shape.ViewPixels() * 3);
  // 8-bit sRGB -> 8-bit Lab goes through OpenCV's lookup tables, an order of magnitude faster than the float path;
  // the quantisation (L steps of 0.4, a/b steps of 1) is far below the colour differences segmentation weighs.
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(static)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    cv::Mat source = light_field.View(view);
    cv::Mat rgb;
    if (light_field.transfer == Transfer::kLinear) {
      source = source.clone();
      source.forEach<float>([](float& value, const int*) { value = EncodeSrgb(value); });
    }
    source.convertTo(rgb, CV_8U, 255.0);
    if (shape.channels == 1) cv::cvtColor(rgb, rgb, cv::COLOR_GRAY2RGB);
    cv::Mat lab8;
    cv::cvtColor(rgb, lab8, cv::COLOR_RGB2Lab);  // 8-bit: L * 255 / 100, a + 128, b + 128
    cv::Mat out = LabView(lab, shape, view);
    for (int y = 0; y < shape.height; ++y) {
      const cv::Vec3b* in = lab8.ptr<cv::Vec3b>(y);
      cv::Vec3f* o = out.ptr<cv::Vec3f>(y);
      for (int x = 0; x < shape.width; ++x) {
        o[x] = {in[x][0] * (100.0f / 255.0f), in[x][1] - 128.0f, in[x][2] - 128.0f};
      }
    }
  }
  return lab;
}

}  // namespace lfsp::segment
