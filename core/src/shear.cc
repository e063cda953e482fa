#include "lfsp/core/shear.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "lfsp/core/error.h"

namespace lfsp {
namespace {

constexpr int kMaxTaps = 4;

// The interpolation taps of one output index along one axis: source indices (already clamped into the image) and
// their weights (zero for taps outside the image when the border is kZero).
struct AxisTaps {
  int count = 0;
  std::vector<std::array<int, kMaxTaps>> index;
  std::vector<std::array<float, kMaxTaps>> weight;
};

// Keys' cubic convolution kernel with a = -0.5 (Catmull-Rom), |t| <= 2.
float KeysCubic(float t) {
  constexpr float a = -0.5f;
  t = std::fabs(t);
  if (t <= 1.0f) return ((a + 2.0f) * t - (a + 3.0f)) * t * t + 1.0f;
  if (t < 2.0f) return ((a * t - 5.0f * a) * t + 8.0f * a) * t - 4.0f * a;
  return 0.0f;
}

// Taps for out(i) = in(i - shift) along an axis of `size` samples. Because the shift is the same for every output
// index, the fractional position and thus the weights are the same too; only the (clamped) indices differ.
AxisTaps MakeAxisTaps(int size, float shift, ShearInterpolation interpolation, ShearBorder border) {
  const double source_offset = -static_cast<double>(shift);
  const double base = std::floor(source_offset);
  const float fraction = static_cast<float>(source_offset - base);
  const int first = static_cast<int>(base);

  AxisTaps taps;
  std::array<float, kMaxTaps> weights{};
  int start = 0;  // offset of the first tap relative to floor(source position)
  if (interpolation == ShearInterpolation::kLinear) {
    taps.count = 2;
    weights = {1.0f - fraction, fraction, 0.0f, 0.0f};
  } else {
    taps.count = 4;
    start = -1;
    weights = {KeysCubic(1.0f + fraction), KeysCubic(fraction), KeysCubic(1.0f - fraction), KeysCubic(2.0f - fraction)};
  }
  taps.index.resize(static_cast<std::size_t>(size));
  taps.weight.resize(static_cast<std::size_t>(size));
  for (int i = 0; i < size; ++i) {
    auto& index = taps.index[static_cast<std::size_t>(i)];
    auto& weight = taps.weight[static_cast<std::size_t>(i)];
    for (int k = 0; k < taps.count; ++k) {
      const long long source = static_cast<long long>(i) + first + start + k;
      const bool inside = source >= 0 && source < size;
      index[static_cast<std::size_t>(k)] =
          inside ? static_cast<int>(source) : (source < 0 ? 0 : size - 1);  // clamped: replicate the edge
      weight[static_cast<std::size_t>(k)] =
          (inside || border == ShearBorder::kReplicate) ? weights[static_cast<std::size_t>(k)] : 0.0f;
    }
  }
  return taps;
}

void CheckShift(ImageShift shift) {
  if (!std::isfinite(shift.dx) || !std::isfinite(shift.dy))
    throw Error("image translation: shift (" + std::to_string(shift.dx) + ", " + std::to_string(shift.dy) +
                ") is not finite");
}

}  // namespace

void TranslateImage(const cv::Mat& in, ImageShift shift, cv::Mat& out, ShearInterpolation interpolation,
                    ShearBorder border) {
  if (in.depth() != CV_32F || in.channels() < 1 || in.channels() > 4 || in.empty())
    throw Error("image translation: expected a non-empty float image with 1-4 channels");
  CheckShift(shift);
  if (out.data == in.data) throw Error("image translation: output must not share memory with the input");
  out.create(in.size(), in.type());

  const int width = in.cols;
  const int height = in.rows;
  const int channels = in.channels();
  const AxisTaps columns = MakeAxisTaps(width, shift.dx, interpolation, border);
  const AxisTaps rows = MakeAxisTaps(height, shift.dy, interpolation, border);
  const std::size_t row_samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);

#pragma omp parallel
  {
    std::vector<float> vertical(row_samples);  // the row interpolated vertically, before the horizontal pass
#pragma omp for schedule(static)
    for (int y = 0; y < height; ++y) {
      const auto& row_index = rows.index[static_cast<std::size_t>(y)];
      const auto& row_weight = rows.weight[static_cast<std::size_t>(y)];
      std::fill(vertical.begin(), vertical.end(), 0.0f);
      for (int k = 0; k < rows.count; ++k) {
        const float w = row_weight[static_cast<std::size_t>(k)];
        if (w == 0.0f) continue;
        const float* source = in.ptr<float>(row_index[static_cast<std::size_t>(k)]);
        for (std::size_t i = 0; i < row_samples; ++i) vertical[i] += w * source[i];
      }
      float* target = out.ptr<float>(y);
      for (int x = 0; x < width; ++x) {
        const auto& column_index = columns.index[static_cast<std::size_t>(x)];
        const auto& column_weight = columns.weight[static_cast<std::size_t>(x)];
        for (int c = 0; c < channels; ++c) {
          float sum = 0.0f;
          for (int k = 0; k < columns.count; ++k)
            sum += column_weight[static_cast<std::size_t>(k)] *
                   vertical[static_cast<std::size_t>(column_index[static_cast<std::size_t>(k)] * channels + c)];
          target[x * channels + c] = sum;
        }
      }
    }
  }
}

void TranslateLabels(const cv::Mat& in, ImageShift shift, cv::Mat& out) {
  if (in.type() != CV_32SC1 || in.empty()) throw Error("label translation: expected a non-empty int32 label image");
  CheckShift(shift);
  if (out.data == in.data) throw Error("label translation: output must not share memory with the input");
  out.create(in.size(), in.type());
  // Nearest neighbour: source = round(x - dx) = x + floor(0.5 - dx), the same offset for every pixel.
  const long long offset_x = static_cast<long long>(std::floor(0.5 - static_cast<double>(shift.dx)));
  const long long offset_y = static_cast<long long>(std::floor(0.5 - static_cast<double>(shift.dy)));
#pragma omp parallel for schedule(static)
  for (int y = 0; y < in.rows; ++y) {
    std::int32_t* target = out.ptr<std::int32_t>(y);
    const long long source_y = y + offset_y;
    if (source_y < 0 || source_y >= in.rows) {
      std::fill(target, target + in.cols, Labels::kUnlabelled);
      continue;
    }
    const std::int32_t* source = in.ptr<std::int32_t>(static_cast<int>(source_y));
    for (int x = 0; x < in.cols; ++x) {
      const long long source_x = x + offset_x;
      target[x] = (source_x >= 0 && source_x < in.cols) ? source[source_x] : Labels::kUnlabelled;
    }
  }
}

LightField ShearLightField(const LightField& light_field, float disparity, const ShearOptions& options) {
  if (light_field.empty()) throw Error("shear: the light field is empty");
  const LightFieldShape& shape = light_field.shape();
  // Checked here, as nothing may throw inside the parallel loop below.
  if (!std::isfinite(disparity)) throw Error("shear: disparity " + std::to_string(disparity) + " is not finite");
  if (shape.channels < 1 || shape.channels > 4)
    throw Error("shear: expected 1-4 channels per ray, got " + std::to_string(shape.channels));
  LightField sheared(shape);
  sheared.transfer = light_field.transfer;
  sheared.metadata = light_field.metadata;
  const bool with_weights = options.weight_outside || light_field.HasWeights();
  if (with_weights) sheared.EnableWeights(0.0f);

  const ViewIndex centre = shape.Centre();
  const cv::Mat ones(shape.height, shape.width, CV_32FC1, cv::Scalar(1.0));
  // One view per thread (TranslateImage's own loop then runs serially): one parallel region for the whole light
  // field keeps threads busy even when the machine is shared.
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const ImageShift shift = ShearShift(view, centre, disparity);
    cv::Mat target = sheared.View(view);
    TranslateImage(light_field.View(view), shift, target, options.interpolation, ShearBorder::kReplicate);
    if (!with_weights) continue;
    cv::Mat target_weights = sheared.WeightView(view);
    if (light_field.HasWeights()) {
      // WeightView is non-const only; wrap the const data without copying (read only).
      const cv::Mat source_weights(shape.height, shape.width, CV_32FC1,
                                   const_cast<float*>(light_field.weights().ViewData(view)));
      TranslateImage(source_weights, shift, target_weights, ShearInterpolation::kLinear, ShearBorder::kZero);
    } else {
      TranslateImage(ones, shift, target_weights, ShearInterpolation::kLinear, ShearBorder::kZero);
    }
  }
  return sheared;
}

Labels ShearLabels(const Labels& labels, float disparity) {
  if (labels.empty()) throw Error("shear: the labels are empty");
  if (!std::isfinite(disparity)) throw Error("shear: disparity " + std::to_string(disparity) + " is not finite");
  const LightFieldShape& shape = labels.shape();
  Labels sheared(shape);
  const ViewIndex centre = shape.Centre();
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    cv::Mat target = sheared.View(view);
    TranslateLabels(labels.View(view), ShearShift(view, centre, disparity), target);
  }
  return sheared;
}

DisparityMap ShearDisparity(const DisparityMap& disparity_map, float disparity) {
  DisparityMap sheared = disparity_map;
  float* values = sheared.data();
  const std::size_t count = static_cast<std::size_t>(sheared.width()) * static_cast<std::size_t>(sheared.height());
  for (std::size_t i = 0; i < count; ++i)
    if (std::isfinite(values[i])) values[i] -= disparity;
  return sheared;
}

}  // namespace lfsp
