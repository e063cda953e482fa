#include "lenslet_slicing.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace lfsp::decode {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

// Bilinear sample of an interleaved float image with kChannels channels at (x, y), clamped to the image.
template <int kChannels>
inline void Bilinear(const float* data, std::size_t stride, int width, int height, double x, double y, float* out) {
  x = std::clamp(x, 0.0, width - 1.0001);
  y = std::clamp(y, 0.0, height - 1.0001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const auto fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  const float* p = data + static_cast<std::size_t>(y0) * stride + static_cast<std::size_t>(x0) * kChannels;
  const float* q = p + stride;
  const float w00 = (1 - fx) * (1 - fy), w01 = fx * (1 - fy), w10 = (1 - fx) * fy, w11 = fx * fy;
  for (int c = 0; c < kChannels; ++c)
    out[c] = w00 * p[c] + w01 * p[kChannels + c] + w10 * q[c] + w11 * q[kChannels + c];
}

// Catmull-Rom (Keys, a = -0.5) weights of the 4 samples around fraction f in [0, 1).
inline void CubicWeights(float f, float* w) {
  const float f2 = f * f, f3 = f2 * f;
  w[0] = -0.5f * f3 + f2 - 0.5f * f;
  w[1] = 1.5f * f3 - 2.5f * f2 + 1.0f;
  w[2] = -1.5f * f3 + 2.0f * f2 + 0.5f * f;
  w[3] = 0.5f * f3 - 0.5f * f2;
}

// Where each output column x of a lens row takes its samples: lens index of the first of 4 taps (in the row's
// buffer, which starts at lens -2) and the 4 weights. The same for every row of one parity.
struct ColumnTaps {
  std::vector<int> first;
  std::vector<float> weights;  // 4 per column
};

ColumnTaps MakeTaps(int width, int shift, int buffer_size) {
  ColumnTaps taps;
  taps.first.resize(static_cast<std::size_t>(width));
  taps.weights.resize(4 * static_cast<std::size_t>(width));
  for (int x = 0; x < width; ++x) {
    const double t = x * kHalfSqrt3 - 0.5 * shift;  // in lens pitches from this row's lens 0
    const double lens = std::floor(t);
    // Buffer index of lens (lens - 1) is lens - 1 + 2.
    const int first = std::clamp(static_cast<int>(lens) + 1, 0, buffer_size - 4);
    CubicWeights(static_cast<float>(t - lens), &taps.weights[4 * static_cast<std::size_t>(x)]);
    // Near the borders the taps were clamped: shift the weights to stay on the same lenses.
    const int wanted = static_cast<int>(lens) + 1;
    if (first != wanted) {
      float w[4] = {0, 0, 0, 0};
      for (int k = 0; k < 4; ++k) {
        const int target = std::clamp(wanted + k - first, 0, 3);
        w[target] += taps.weights[4 * static_cast<std::size_t>(x) + static_cast<std::size_t>(k)];
      }
      std::copy(w, w + 4, &taps.weights[4 * static_cast<std::size_t>(x)]);
    }
    taps.first[static_cast<std::size_t>(x)] = first;
  }
  return taps;
}

}  // namespace

void SliceLensletImage(const cv::Mat& rgb, const cv::Mat& grey_white, const LensletGrid& grid,
                       const DecodedGeometry& geometry, LightField& light_field) {
  const int views = geometry.views;
  const int centre = (views - 1) / 2;
  const int width = geometry.width;
  // Lenses -2 .. columns + 1 of a row, so every output column has its 4 taps.
  const int lens_begin = -2;
  const int buffer_size = grid.columns + 4;
  const ColumnTaps taps[2] = {MakeTaps(width, 0, buffer_size), MakeTaps(width, 1, buffer_size)};
  const double c = std::cos(grid.rotation), s = std::sin(grid.rotation);
  const double pitch_x = c * grid.spacing_x, pitch_y = s * grid.spacing_x;
  // Rays beyond the micro-lens radius see the neighbouring micro-image: they get no weight.
  const double lens_radius = 0.5 * grid.spacing_x;
  const float* rgb_data = rgb.ptr<float>(0);
  const std::size_t rgb_stride = rgb.step1();
  const float* white_data = grey_white.ptr<float>(0);
  const std::size_t white_stride = grey_white.step1();
#pragma omp parallel
  {
    std::vector<float> colour(3 * static_cast<std::size_t>(buffer_size));
    std::vector<float> white(static_cast<std::size_t>(buffer_size));
#pragma omp for schedule(dynamic, 1)
    for (int y = 0; y < geometry.height; ++y) {
      const int shift = grid.Shift(y);
      const ColumnTaps& row_taps = taps[shift];
      for (int v = 0; v < views; ++v)
        for (int u = 0; u < views; ++u) {
          const ViewIndex view{u, v};
          const double along = (u - centre) * geometry.view_step, across = (v - centre) * geometry.view_step;
          const bool inside_lens = std::hypot(along, across) < lens_radius;
          // This view's sample of every lens of the row (one bilinear look-up each).
          double px = 0.0, py = 0.0;
          grid.SensorPosition(lens_begin + 0.5 * shift, y, along, across, px, py);
          for (int k = 0; k < buffer_size; ++k) {
            Bilinear<3>(rgb_data, rgb_stride, rgb.cols, rgb.rows, px, py, &colour[3 * static_cast<std::size_t>(k)]);
            Bilinear<1>(white_data, white_stride, grey_white.cols, grey_white.rows, px, py,
                        &white[static_cast<std::size_t>(k)]);
            px += pitch_x;
            py += pitch_y;
          }
          // Hexagonal to rectangular: cubic interpolation along the lens row.
          float* out = light_field.ViewData(view) + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 3;
          float* weight_out =
              light_field.weights().ViewData(view) + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
          for (int x = 0; x < width; ++x) {
            const int first = row_taps.first[static_cast<std::size_t>(x)];
            const float* w = &row_taps.weights[4 * static_cast<std::size_t>(x)];
            const float* p = &colour[3 * static_cast<std::size_t>(first)];
            for (int ch = 0; ch < 3; ++ch)
              out[3 * x + ch] = w[0] * p[ch] + w[1] * p[3 + ch] + w[2] * p[6 + ch] + w[3] * p[9 + ch];
            const float* q = &white[static_cast<std::size_t>(first)];
            weight_out[x] = inside_lens ? w[0] * q[0] + w[1] * q[1] + w[2] * q[2] + w[3] * q[3] : 0.0f;
          }
        }
    }
  }
}

void SoftenRowAlternation(LightField& light_field, float alpha) {
  if (alpha <= 0.0f) return;
  const LightFieldShape& shape = light_field.shape();
  const std::size_t row_size = static_cast<std::size_t>(shape.width) * static_cast<std::size_t>(shape.channels);
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel
  {
    std::vector<float> previous(row_size), current(row_size);
#pragma omp for schedule(dynamic, 1)
    for (int k = 0; k < views; ++k) {
      float* view = light_field.ViewData(ViewFromCameraNumber(k, shape.nu));
      std::copy(view, view + row_size, previous.begin());
      for (int y = 1; y + 1 < shape.height; ++y) {
        float* row = view + static_cast<std::size_t>(y) * row_size;
        const float* next = row + row_size;
        std::copy(row, row + row_size, current.begin());
        for (std::size_t i = 0; i < row_size; ++i)
          row[i] = (1.0f - 2.0f * alpha) * current[i] + alpha * (previous[i] + next[i]);
        std::swap(previous, current);
      }
    }
  }
}

}  // namespace lfsp::decode
