#include "lenslet_slicing.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "lfsp/core/memory_usage.h"
#include "lfsp/core/srgb.h"

namespace lfsp::decode {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

// The four bilinear taps at (x0, y0) .. (x0 + 1, y0 + 1) of the RGB image and the grey white image, 4 values each
// (R, G, B, white). A tap under another micro-lens than `lens` (LensLabels) sees another part of the scene, so its
// value is replaced by a linear extrapolation from the taps under this lens (and, where only one row or column of
// taps is, from the pixels one step further in). Leaving such a tap out and renormalising the rest, as the slicing
// did before, moves the sample towards the lens centre, that is, towards the centre view: the F01's corner views
// ((+-3, +-3) of the central 7x7, 4.2 px out, whose outer diagonal tap often lies across the cell boundary at
// 5.1 px) were sampled 1.5-2 % of their offset inwards, which read every strip of e2e/full_size 0.3-0.5 % closer to
// d = 0. Extrapolation is exact for a linear signal, so it keeps the sample where it is. Where the pixels further in
// are not under the lens either, the missing tap takes its neighbour's value (the old behaviour).
class Taps {
 public:
  Taps(const cv::Mat& rgb, const cv::Mat& grey, const cv::Mat& labels, std::uint8_t lens, int x0, int y0)
      : rgb_(rgb), grey_(grey), labels_(labels), lens_(lens), x0_(x0), y0_(y0) {
    for (int k = 0; k < 4; ++k) {
      const int dx = k & 1, dy = k >> 1;
      kept_[k] = Inside(dx, dy);
      Read(dx, dy, value_[k]);
    }
  }

  // Fills in the taps under other lenses. When none is under this lens, the values are left as read.
  void Complete() {
    const int count = kept_[0] + kept_[1] + kept_[2] + kept_[3];
    if (count == 4 || count == 0) return;
    if (count == 3) {
      // The plane through the other three: missing = its two neighbours - the opposite tap.
      const int missing = !kept_[0] ? 0 : !kept_[1] ? 1 : !kept_[2] ? 2 : 3;
      for (int c = 0; c < 4; ++c)
        value_[missing][c] = value_[missing ^ 1][c] + value_[missing ^ 2][c] - value_[missing ^ 3][c];
      return;
    }
    if (count == 2 && kept_[0] == kept_[1]) {  // one row kept: extrapolate across the rows
      const int row = kept_[0] ? 0 : 1, beyond = row == 0 ? -1 : 2;
      for (int dx = 0; dx < 2; ++dx) Extend(dx + 2 * row, dx, beyond, dx + 2 * (1 - row));
      return;
    }
    if (count == 2 && kept_[0] == kept_[2]) {  // one column kept: extrapolate across the columns
      const int column = kept_[0] ? 0 : 1, beyond = column == 0 ? -1 : 2;
      for (int dy = 0; dy < 2; ++dy) Extend(column + 2 * dy, beyond, dy, (1 - column) + 2 * dy);
      return;
    }
    if (count == 2) {  // two diagonal taps: the missing ones take their mean (the plane without a cross slope)
      const int a = kept_[0] ? 0 : 1;
      for (int c = 0; c < 4; ++c) value_[a ^ 1][c] = value_[a ^ 2][c] = 0.5f * (value_[a][c] + value_[a ^ 3][c]);
      return;
    }
    // One tap: extrapolate along each axis from the pixels further in, then the plane through the three.
    const int kept = kept_[0] ? 0 : kept_[1] ? 1 : kept_[2] ? 2 : 3;
    const int dx = kept & 1, dy = kept >> 1;
    Extend(kept, dx == 0 ? -1 : 2, dy, kept ^ 1);
    Extend(kept, dx, dy == 0 ? -1 : 2, kept ^ 2);
    for (int c = 0; c < 4; ++c) value_[kept ^ 3][c] = value_[kept ^ 1][c] + value_[kept ^ 2][c] - value_[kept][c];
  }

  const float* Value(int k) const { return value_[k]; }

 private:
  bool Inside(int dx, int dy) const {
    const int x = x0_ + dx, y = y0_ + dy;
    return x >= 0 && y >= 0 && x < labels_.cols && y < labels_.rows && labels_.at<std::uint8_t>(y, x) == lens_;
  }
  void Read(int dx, int dy, float* out) const {
    const float* p = rgb_.ptr<float>(y0_ + dy) + 3 * (x0_ + dx);
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2];
    out[3] = grey_.at<float>(y0_ + dy, x0_ + dx);
  }
  // Tap `to` = 2 x tap `from` - the pixel at (bx, by) beyond `from`, or tap `from` where that pixel is not under
  // this lens.
  void Extend(int from, int bx, int by, int to) {
    if (Inside(bx, by)) {
      float beyond[4];
      Read(bx, by, beyond);
      for (int c = 0; c < 4; ++c) value_[to][c] = 2.0f * value_[from][c] - beyond[c];
    } else {
      for (int c = 0; c < 4; ++c) value_[to][c] = value_[from][c];
    }
  }

  const cv::Mat& rgb_;
  const cv::Mat& grey_;
  const cv::Mat& labels_;
  std::uint8_t lens_;
  int x0_, y0_;
  bool kept_[4]{};
  float value_[4][4]{};
};

// The bilinear sample with weights `w` of the taps at (x0, y0) .. (x0 + 1, y0 + 1), one or two of them under
// another lens (Taps). Kept out of line: it is rare, and inlined it slowed the common path.
[[gnu::noinline]] void SampleCompleted(const cv::Mat& rgb, const cv::Mat& grey, const cv::Mat& labels,
                                       std::uint8_t lens, int x0, int y0, const float* w, float* colour, float* white) {
  Taps taps(rgb, grey, labels, lens, x0, y0);
  taps.Complete();
  const float* a = taps.Value(0);
  const float* b = taps.Value(1);
  const float* c = taps.Value(2);
  const float* d = taps.Value(3);
  for (int k = 0; k < 3; ++k) colour[k] = w[0] * a[k] + w[1] * b[k] + w[2] * c[k] + w[3] * d[k];
  *white = w[0] * a[3] + w[1] * b[3] + w[2] * c[3] + w[3] * d[3];
}

// Bilinear samples of the RGB image and the grey white image at the same sensor point (x, y), clamped to the
// image: the position, the 4 weights and the addresses are computed once for both. Taps under another micro-lens
// than `lens` are extrapolated from those under it (Taps): the outer views' samples lie within 1.5 px of the
// boundary with the next lens, whose micro-image sees another part of the scene.
inline void SampleBoth(const cv::Mat& rgb, const cv::Mat& grey, const cv::Mat& labels, std::uint8_t lens, double x,
                       double y, float* colour, float* white) {
  x = std::clamp(x, 0.0, rgb.cols - 1.0001);
  y = std::clamp(y, 0.0, rgb.rows - 1.0001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const auto fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
  float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};  // taps 00, 01, 10, 11
  const std::uint8_t* l = labels.ptr<std::uint8_t>(y0) + x0;
  const std::uint8_t* m = labels.ptr<std::uint8_t>(y0 + 1) + x0;
  if ((l[0] != lens) | (l[1] != lens) | (m[0] != lens) | (m[1] != lens)) {
    const bool kept[4] = {l[0] == lens, l[1] == lens, m[0] == lens, m[1] == lens};
    const int count = kept[0] + kept[1] + kept[2] + kept[3];
    if (count == 3) {
      // The common case at the rim, without reading anything more: the missing tap's value is its two neighbours
      // minus the opposite tap (Taps), so its weight moves onto those three.
      const int missing = !kept[0] ? 0 : !kept[1] ? 1 : !kept[2] ? 2 : 3;
      w[missing ^ 1] += w[missing];
      w[missing ^ 2] += w[missing];
      w[missing ^ 3] -= w[missing];
      w[missing] = 0.0f;
    } else if (count > 0) {
      SampleCompleted(rgb, grey, labels, lens, x0, y0, w, colour, white);
      return;
    }
  }
  const float* p = rgb.ptr<float>(y0) + 3 * x0;
  const float* q = rgb.ptr<float>(y0 + 1) + 3 * x0;
  for (int c = 0; c < 3; ++c) colour[c] = w[0] * p[c] + w[1] * p[3 + c] + w[2] * q[c] + w[3] * q[3 + c];
  const float* g = grey.ptr<float>(y0) + x0;
  const float* h = grey.ptr<float>(y0 + 1) + x0;
  *white = w[0] * g[0] + w[1] * g[1] + w[2] * h[0] + w[3] * h[1];
}

// The exposure is set from this quantile of the brightest channel of well-lit rays, not from the single brightest:
// sensor noise amplified by devignetting, demosaicking and the colour matrix put the maximum of a well-exposed
// mini-Illum capture at 1.16 (scene at most 0.67), which darkened the whole light field by 14 %.
constexpr double kBrightQuantile = 0.9999;

// Catmull-Rom (Keys, a = -0.5) weights of the 4 samples around fraction f in [0, 1).
inline void CubicWeights(float f, float* w) {
  const float f2 = f * f, f3 = f2 * f;
  w[0] = -0.5f * f3 + f2 - 0.5f * f;
  w[1] = 1.5f * f3 - 2.5f * f2 + 1.0f;
  w[2] = -1.5f * f3 + 2.0f * f2 + 0.5f * f;
  w[3] = 0.5f * f3 - 0.5f * f2;
}

// Where each output column x of a lens row takes its samples: the buffer index of the first of 4 taps (the buffer
// starts at lens -2) and the 4 weights. The same for every row of one parity.
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
    const int wanted = static_cast<int>(lens) + 1;  // buffer index of lens (lens - 1)
    const int first = std::clamp(wanted, 0, buffer_size - 4);
    float* w = &taps.weights[4 * static_cast<std::size_t>(x)];
    CubicWeights(static_cast<float>(t - lens), w);
    if (first != wanted) {  // clamped at a border: keep each weight on its lens, folded onto the buffer's end
      float folded[4] = {0, 0, 0, 0};
      for (int k = 0; k < 4; ++k) folded[std::clamp(wanted + k - first, 0, 3)] += w[k];
      std::copy(folded, folded + 4, w);
    }
    taps.first[static_cast<std::size_t>(x)] = first;
  }
  return taps;
}

// sRGB encoding through a table (the curve is smooth; 4096 linear segments are exact to ~1e-5).
class SrgbTable {
 public:
  SrgbTable() {
    for (int k = 0; k <= kSize; ++k) {
      const double linear = static_cast<double>(k) / kSize;
      table_[static_cast<std::size_t>(k)] = static_cast<float>(LinearToSrgb(linear));
    }
  }
  float operator()(float linear) const {
    const float position = std::clamp(linear, 0.0f, 1.0f) * kSize;
    const int k = std::min(kSize - 1, static_cast<int>(position));
    const float f = position - static_cast<float>(k);
    const auto i = static_cast<std::size_t>(k);
    return table_[i] + f * (table_[i + 1] - table_[i]);
  }

 private:
  static constexpr int kSize = 4096;
  std::array<float, kSize + 1> table_{};
};

// Where the rays of view (u, v) of the geometry's whole grid meet the sensor, from their lens's centre, in the
// lattice frame (pixels along and across the lens rows), and whether that point lies inside the micro-lens: the
// slicing and the estimate of the views' weights must agree on both.
struct ViewOffset {
  double along = 0.0;
  double across = 0.0;
  bool inside_lens = false;
};

ViewOffset GridViewOffset(const DecodedGeometry& geometry, const LensletGrid& grid, int u, int v) {
  const int centre = (geometry.views - 1) / 2;
  ViewOffset offset;
  offset.along = (u - centre) * geometry.view_step;
  offset.across = (v - centre) * geometry.view_step;
  // Rays beyond the micro-lens radius see the neighbouring micro-image: they get no weight.
  offset.inside_lens = std::hypot(offset.along, offset.across) < 0.5 * grid.spacing_x;
  return offset;
}

// Gives back the sensor rows behind the slicing. Lens rows finish out of order across the threads; the rows above
// the first lens row not yet done, less the reach of its lookups, are read by no lens row still to come.
class SensorRowsBehind {
 public:
  // `first_row_read(j)`: the first sensor row that lens row j, or any row after it, reads.
  SensorRowsBehind(const std::vector<cv::Mat*>& images, int lens_rows, std::function<int(int)> first_row_read)
      : images_(images), done_(static_cast<std::size_t>(lens_rows), 0), first_row_read_(std::move(first_row_read)) {}

  void Done(int lens_row) {
    if (images_.empty()) return;
#pragma omp critical(lfsp_slice_rows_behind)
    {
      const int lens_rows = static_cast<int>(done_.size());
      done_[static_cast<std::size_t>(lens_row)] = 1;
      while (next_ < lens_rows && done_[static_cast<std::size_t>(next_)]) ++next_;
      const int until = next_ < lens_rows ? first_row_read_(next_) : std::numeric_limits<int>::max();
      if (until > discarded_) {
        for (cv::Mat* image : images_) DiscardRows(*image, discarded_, until);
        discarded_ = until;
      }
    }
  }

 private:
  static void DiscardRows(cv::Mat& image, int from, int to) {
    to = std::min(to, image.rows);
    if (to <= from || !image.isContinuous()) return;
    DiscardPages(image.ptr(from), image.data + static_cast<std::size_t>(to) * image.step[0]);
  }

  std::vector<cv::Mat*> images_;
  std::vector<char> done_;
  std::function<int(int)> first_row_read_;
  int next_ = 0;       // the first lens row not yet done
  int discarded_ = 0;  // sensor rows [0, discarded_) are given back
};

}  // namespace

void SliceLensletImage(const cv::Mat& rgb, const cv::Mat& grey_white, const cv::Mat& lens_labels,
                       const LensletGrid& grid, const DecodedGeometry& geometry, const RayColour& colour,
                       LightField& light_field, const std::vector<cv::Mat*>& discard_behind) {
  // The light field holds the central views x views of the geometry's grid (all of them unless fewer were asked).
  const int views = light_field.shape().nu;
  const int first_view = (geometry.views - views) / 2;
  const int width = geometry.width;
  // Lenses -2 .. columns + 1 of a row, so every output column has its 4 taps.
  const int lens_begin = -2;
  const int buffer_size = grid.columns + 4;
  const ColumnTaps taps[2] = {MakeTaps(width, 0, buffer_size), MakeTaps(width, 1, buffer_size)};
  const double c = std::cos(grid.rotation), s = std::sin(grid.rotation);
  const double pitch_x = c * grid.spacing_x, pitch_y = s * grid.spacing_x;
  std::array<float, 9> m = colour.matrix;
  for (float& value : m) value *= colour.scale;
  // Per view: the sensor offset of its rays from a lens centre, and whether they stay inside the lens.
  const int view_count = views * views;
  std::vector<double> offset_x(static_cast<std::size_t>(view_count)), offset_y(static_cast<std::size_t>(view_count));
  std::vector<char> inside_lens(static_cast<std::size_t>(view_count));
  for (int v = 0; v < views; ++v)
    for (int u = 0; u < views; ++u) {
      const auto k = static_cast<std::size_t>(v * views + u);
      const ViewOffset offset = GridViewOffset(geometry, grid, first_view + u, first_view + v);
      offset_x[k] = c * offset.along - s * offset.across;
      offset_y[k] = s * offset.along + c * offset.across;
      inside_lens[k] = offset.inside_lens;
    }
  const std::size_t lenses = static_cast<std::size_t>(buffer_size);
  // The first sensor row lens row j reads: its highest lens centre (the rotation tilts the row), moved by the views'
  // most negative offset, less the taps' reach (SampleBoth's 2 x 2, and the pixel above it that Taps may extrapolate
  // from) and a row of margin. Later lens rows lie lower.
  double lowest_offset_y = 0.0;
  for (int k = 0; k < view_count; ++k)
    if (inside_lens[static_cast<std::size_t>(k)])
      lowest_offset_y = std::min(lowest_offset_y, offset_y[static_cast<std::size_t>(k)]);
  const auto first_row_read = [&](int y) {
    double x_first = 0.0, y_first = 0.0, x_last = 0.0, y_last = 0.0;
    const double start = lens_begin + 0.5 * grid.Shift(y);
    grid.SensorPosition(start, y, 0.0, 0.0, x_first, y_first);
    grid.SensorPosition(start + static_cast<double>(lenses - 1), y, 0.0, 0.0, x_last, y_last);
    constexpr int kTapReach = 2;
    return static_cast<int>(std::floor(std::min(y_first, y_last) + lowest_offset_y)) - kTapReach;
  };
  SensorRowsBehind behind(discard_behind, geometry.height, first_row_read);
#pragma omp parallel
  {
    // Every view's sample of every lens of one row: [view][lens][rgb] and [view][lens].
    std::vector<float> samples(static_cast<std::size_t>(view_count) * lenses * 3);
    std::vector<float> white(static_cast<std::size_t>(view_count) * lenses);
#pragma omp for schedule(dynamic, 1)
    for (int y = 0; y < geometry.height; ++y) {
      const int shift = grid.Shift(y);
      const ColumnTaps& row_taps = taps[shift];
      // Lens by lens, all views: the look-ups of one lens stay within its micro-image (cache-resident).
      double cx = 0.0, cy = 0.0;
      grid.SensorPosition(lens_begin + 0.5 * shift, y, 0.0, 0.0, cx, cy);
      for (std::size_t lens = 0; lens < lenses; ++lens, cx += pitch_x, cy += pitch_y) {
        const int i = lens_begin + static_cast<int>(lens);
        const auto label = static_cast<std::uint8_t>((i & 3) + 4 * (y & 1));  // as LensLabels
        for (std::size_t k = 0; k < static_cast<std::size_t>(view_count); ++k) {
          if (!inside_lens[k]) continue;
          float in[3];
          SampleBoth(rgb, grey_white, lens_labels, label, cx + offset_x[k], cy + offset_y[k], in,
                     &white[k * lenses + lens]);
          float* out = &samples[(k * lenses + lens) * 3];
          out[0] = m[0] * in[0] + m[1] * in[1] + m[2] * in[2];
          out[1] = m[3] * in[0] + m[4] * in[1] + m[5] * in[2];
          out[2] = m[6] * in[0] + m[7] * in[1] + m[8] * in[2];
        }
      }
      // Hexagonal to rectangular, view by view: cubic interpolation along the lens row.
      for (int k = 0; k < view_count; ++k) {
        const ViewIndex view = ViewFromCameraNumber(k, views);
        const float* view_samples = &samples[static_cast<std::size_t>(k) * lenses * 3];
        const float* view_white = &white[static_cast<std::size_t>(k) * lenses];
        const bool lit = inside_lens[static_cast<std::size_t>(k)] != 0;
        float* out = light_field.ViewData(view) + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 3;
        float* weight_out =
            light_field.weights().ViewData(view) + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
        if (!lit) {  // as LFToolbox: rays beyond the lens radius are black, with no weight
          std::fill(out, out + 3 * static_cast<std::size_t>(width), 0.0f);
          std::fill(weight_out, weight_out + width, 0.0f);
          continue;
        }
        for (int x = 0; x < width; ++x) {
          const auto first = static_cast<std::size_t>(row_taps.first[static_cast<std::size_t>(x)]);
          const float* w = &row_taps.weights[4 * static_cast<std::size_t>(x)];
          const float* p = view_samples + 3 * first;
          // Not clamped: linear light keeps its signed noise (the colour matrix amplifies it, and clipping the
          // negative half brightened a dim capture by 18 %); the sRGB encoding of camera colour clamps.
          for (int ch = 0; ch < 3; ++ch)
            out[3 * x + ch] = w[0] * p[ch] + w[1] * p[3 + ch] + w[2] * p[6 + ch] + w[3] * p[9 + ch];
          const float* q = view_white + first;
          weight_out[x] = std::clamp(w[0] * q[0] + w[1] * q[1] + w[2] * q[2] + w[3] * q[3], 0.0f, 1.0f);
        }
      }
      behind.Done(y);
    }
  }
}

std::vector<double> ApproximateViewMeanWeights(const cv::Mat& grey_white, const LensletGrid& grid,
                                               const DecodedGeometry& geometry) {
  constexpr int kRowStep = 4;
  const int views = geometry.views;
  std::vector<double> means(static_cast<std::size_t>(views) * static_cast<std::size_t>(views), 0.0);
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < views * views; ++k) {
    const ViewOffset offset = GridViewOffset(geometry, grid, k % views, k / views);
    if (!offset.inside_lens) continue;  // the slicing gives these rays no weight
    double sum = 0.0;
    long long count = 0;
    for (int y = 0; y < geometry.height; y += kRowStep)
      for (int i = 0; i < grid.columns; ++i) {
        double x = 0.0, sy = 0.0;
        grid.SensorPosition(i + 0.5 * grid.Shift(y), y, offset.along, offset.across, x, sy);
        x = std::clamp(x, 0.0, grey_white.cols - 1.0001);
        sy = std::clamp(sy, 0.0, grey_white.rows - 1.0001);
        const int x0 = static_cast<int>(x), y0 = static_cast<int>(sy);
        const double fx = x - x0, fy = sy - y0;
        const float* g = grey_white.ptr<float>(y0) + x0;
        const float* h = grey_white.ptr<float>(y0 + 1) + x0;
        const double white = (1 - fx) * (1 - fy) * g[0] + fx * (1 - fy) * g[1] + (1 - fx) * fy * h[0] + fx * fy * h[1];
        sum += std::clamp(white, 0.0, 1.0);
        ++count;
      }
    means[static_cast<std::size_t>(k)] = count > 0 ? sum / static_cast<double>(count) : 0.0;
  }
  return means;
}

float BrightestWellLit(const cv::Mat& rgb, const cv::Mat& grey_white, const std::array<float, 9>& m) {
  // One pass: a histogram of the brightest channel over [0, kTop) (devignetted sensor values stay far below it;
  // anything above falls in the last bin), then its kBrightQuantile level.
  constexpr float kTop = 8.0f;
  constexpr int kBins = 32768;  // steps of 2.4e-4
  std::vector<long long> histogram(kBins, 0);
  long long lit = 0;
#pragma omp parallel reduction(+ : lit)
  {
    std::vector<long long> local(kBins, 0);
#pragma omp for schedule(static)
    for (int y = 0; y < rgb.rows; ++y) {
      const float* p = rgb.ptr<float>(y);
      const float* w = grey_white.ptr<float>(y);
      for (int x = 0; x < rgb.cols; ++x) {
        if (w[x] < 0.5f) continue;
        const float* in = p + 3 * x;
        const float brightest =
            std::max({m[0] * in[0] + m[1] * in[1] + m[2] * in[2], m[3] * in[0] + m[4] * in[1] + m[5] * in[2],
                      m[6] * in[0] + m[7] * in[1] + m[8] * in[2]});
        const int bin = static_cast<int>(std::clamp(brightest, 0.0f, kTop) * (kBins / kTop));
        ++local[static_cast<std::size_t>(std::min(kBins - 1, bin))];
        ++lit;
      }
    }
#pragma omp critical
    for (int k = 0; k < kBins; ++k) histogram[static_cast<std::size_t>(k)] += local[static_cast<std::size_t>(k)];
  }
  if (lit == 0) return 0.0f;
  const auto wanted = static_cast<long long>(kBrightQuantile * static_cast<double>(lit));
  long long count = 0;
  int bin = 0;
  while (bin < kBins - 1 && count + histogram[static_cast<std::size_t>(bin)] < wanted)
    count += histogram[static_cast<std::size_t>(bin++)];
  return (static_cast<float>(bin) + 1.0f) * (kTop / kBins);
}

void SoftenAndEncode(LightField& light_field, float alpha, bool srgb) {
  if (alpha <= 0.0f && !srgb) return;
  static const SrgbTable encode;
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
      for (int y = 0; y < shape.height; ++y) {
        float* row = view + static_cast<std::size_t>(y) * row_size;
        if (alpha > 0.0f && y > 0 && y + 1 < shape.height) {
          const float* next = row + row_size;
          std::copy(row, row + row_size, current.begin());
          for (std::size_t i = 0; i < row_size; ++i)
            row[i] = (1.0f - 2.0f * alpha) * current[i] + alpha * (previous[i] + next[i]);
          std::swap(previous, current);
        }
        // Row y - 1 is final once row y has been softened (it needed y - 1's original only): encode it now.
        if (srgb && y > 0) {
          float* done = row - row_size;
          for (std::size_t i = 0; i < row_size; ++i) done[i] = encode(done[i]);
        }
      }
      if (srgb) {
        float* last = view + static_cast<std::size_t>(shape.height - 1) * row_size;
        for (std::size_t i = 0; i < row_size; ++i) last[i] = encode(last[i]);
      }
    }
  }
}

}  // namespace lfsp::decode
