#include "lfsp/depth/cost_volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <string>

#include "lfsp/core/conventions.h"
#include "lfsp/core/error.h"

namespace lfsp::depth {
namespace {

// One non-centre view: where its samples are, how far it sits from the centre view, and its angular sector.
struct ViewPlan {
  const float* colour;  // interleaved RGB rows of the view
  const float* detail;  // the same for its detail image (nullptr without the detail term)
  float du;             // u - uc
  float dv;             // v - vc
  int sector;
};

// Bilinear samples of one view row at (x + sx, y + sy), compared with the centre row, added to `accumulator`:
// accumulator[x] += weight * min(sum over channels of |sample - centre|, truncation); rows hold `channels`
// interleaved samples per pixel (1 or 3). Samples beyond the border are clamped. Built twice (AVX2 and generic) and
// chosen at run time, so the interleaved inner loop vectorises where it can.
__attribute__((target_clones("avx2", "default"))) void AccumulateRowCost(const float* view, int channels, int width,
                                                                         int height, int y, float sx, float sy,
                                                                         const float* centre_row, float deadzone,
                                                                         float truncation, float weight,
                                                                         float* differences, float* accumulator) {
  const float fx = std::floor(sx);
  const float fy = std::floor(sy);
  const float ax = sx - fx;
  const float ay = sy - fy;
  const int ix = static_cast<int>(fx);
  const int iy = static_cast<int>(fy);
  const int y0 = std::clamp(y + iy, 0, height - 1);
  const int y1 = std::clamp(y + iy + 1, 0, height - 1);
  const std::size_t stride = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  const float* row0 = view + static_cast<std::size_t>(y0) * stride;
  const float* row1 = view + static_cast<std::size_t>(y1) * stride;
  const float w00 = (1.0f - ax) * (1.0f - ay);
  const float w01 = ax * (1.0f - ay);
  const float w10 = (1.0f - ax) * ay;
  const float w11 = ax * ay;

  // Columns whose two taps are both inside the row: one contiguous run over the interleaved samples.
  const int x_begin = std::clamp(-ix, 0, width);
  const int x_end = std::clamp(width - 1 - ix, x_begin, width);
  const int shift = channels * ix;
  for (int p = channels * x_begin; p < channels * x_end; ++p) {
    const int q = p + shift;
    const float sample = w00 * row0[q] + w01 * row0[q + channels] + w10 * row1[q] + w11 * row1[q + channels];
    differences[p] = std::abs(sample - centre_row[p]);
  }
  // The few columns near the border: clamp each tap.
  auto clamped = [&](int x) {
    const int c0 = std::clamp(x + ix, 0, width - 1) * channels;
    const int c1 = std::clamp(x + ix + 1, 0, width - 1) * channels;
    for (int c = 0; c < channels; ++c) {
      const float sample = w00 * row0[c0 + c] + w01 * row0[c1 + c] + w10 * row1[c0 + c] + w11 * row1[c1 + c];
      differences[channels * x + c] = std::abs(sample - centre_row[channels * x + c]);
    }
  };
  for (int x = 0; x < x_begin; ++x) clamped(x);
  for (int x = x_end; x < width; ++x) clamped(x);

  if (channels == 3) {
    for (int x = 0; x < width; ++x) {
      const float sum = differences[3 * x] + differences[3 * x + 1] + differences[3 * x + 2];
      accumulator[x] += weight * std::min(std::max(sum - deadzone, 0.0f), truncation);
    }
  } else {
    for (int x = 0; x < width; ++x) {
      accumulator[x] += weight * std::min(std::max(differences[x] - deadzone, 0.0f), truncation);
    }
  }
}

// The high-pass detail image of every view, grey (mean of RGB; the colour of faint texture adds little, measured),
// one channel, views in the light field's order.
std::vector<float> MakeDetailImages(const LightField& light_field, const CostOptions& options) {
  const float sigma = options.detail_sigma;
  const LightFieldShape& shape = light_field.shape();
  std::vector<float> detail(shape.Views() * shape.ViewPixels());
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < views; ++i) {
    const ViewIndex view = ViewFromCameraNumber(i, shape.nu);
    cv::Mat grey;
    cv::transform(light_field.View(view), grey, cv::Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
    cv::Mat target(shape.height, shape.width, CV_32FC1,
                   detail.data() + static_cast<std::size_t>(i) * shape.ViewPixels());
    cv::GaussianBlur(grey, target, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
    cv::subtract(grey, target, target);
    if (options.detail_normalise_sigma > 0.0f) {
      cv::Mat energy;
      cv::multiply(target, target, energy);
      cv::GaussianBlur(energy, energy, cv::Size(), options.detail_normalise_sigma, options.detail_normalise_sigma,
                       cv::BORDER_REFLECT);
      cv::sqrt(energy, energy);
      energy += options.detail_normalise_epsilon;
      cv::divide(target, energy, target);
    }
  }
  return detail;
}

const float* DetailView(const std::vector<float>& detail, const LightFieldShape& shape, ViewIndex view) {
  return detail.data() + static_cast<std::size_t>(CameraNumber(view, shape.nu)) * shape.ViewPixels();
}

std::vector<ViewPlan> PlanViews(const LightField& light_field, const std::vector<float>& detail) {
  const LightFieldShape& shape = light_field.shape();
  const ViewIndex centre = shape.Centre();
  std::vector<ViewPlan> plans;
  for (int v = 0; v < shape.nv; ++v) {
    for (int u = 0; u < shape.nu; ++u) {
      if (u == centre.u && v == centre.v) continue;
      const float* detail_view = detail.empty() ? nullptr : DetailView(detail, shape, {u, v});
      plans.push_back({light_field.ViewData({u, v}), detail_view, static_cast<float>(u - centre.u),
                       static_cast<float>(v - centre.v), SectorOfOffset(u - centre.u, v - centre.v)});
    }
  }
  return plans;
}

// Which sectors form half A of each split (half B is the complement), and how many views each half holds.
struct SplitTable {
  std::array<std::array<bool, kSectors>, kSplits> in_half_a{};
  std::array<float, kSplits> views_a{};
  std::array<float, kSplits> views_b{};
};

SplitTable MakeSplitTable(const std::vector<ViewPlan>& plans) {
  SplitTable table;
  for (int j = 0; j < kSplits; ++j) {
    for (int k = 0; k < kSectors / 2; ++k) table.in_half_a[j][(j + k) % kSectors] = true;
    for (const ViewPlan& plan : plans) (table.in_half_a[j][plan.sector] ? table.views_a[j] : table.views_b[j]) += 1;
  }
  return table;
}

void CheckInput(const LightField& light_field, const std::vector<float>& disparities, const OcclusionMap* occlusion) {
  const LightFieldShape& shape = light_field.shape();
  if (light_field.empty() || shape.channels != 3) {
    throw Error("depth: the light field must hold RGB views (got " + ToString(shape) + ")");
  }
  if (shape.nu * shape.nv < 2) throw Error("depth: at least two views are needed (got " + ToString(shape) + ")");
  if (disparities.size() < 3) throw Error("depth: at least 3 disparity labels are needed");
  if (occlusion != nullptr && (occlusion->candidate.rows != shape.height || occlusion->candidate.cols != shape.width)) {
    throw Error("depth: occlusion map size differs from the views");
  }
}

}  // namespace

std::vector<float> LabelDisparities(float min, float max, int count) {
  if (count < 3) throw Error("depth: --labels must be at least 3 (got " + std::to_string(count) + ")");
  if (!(max > min)) {
    throw Error("depth: disparity range is empty (min " + std::to_string(min) + ", max " + std::to_string(max) + ")");
  }
  std::vector<float> disparities(static_cast<std::size_t>(count));
  for (int l = 0; l < count; ++l) {
    disparities[static_cast<std::size_t>(l)] =
        min + (max - min) * static_cast<float>(l) / static_cast<float>(count - 1);
  }
  return disparities;
}

CostVolume BuildCostVolume(const LightField& light_field, const std::vector<float>& disparities,
                           const CostOptions& options, const OcclusionMap* occlusion) {
  CheckInput(light_field, disparities, occlusion);
  const LightFieldShape& shape = light_field.shape();
  const int width = shape.width;
  const int height = shape.height;
  const int labels = static_cast<int>(disparities.size());
  const bool use_detail = options.detail_sigma > 0.0f;
  const bool use_colour = options.colour_weight > 0.0f;
  if (!use_detail && !use_colour) throw Error("depth: the cost needs the detail or the colour term");
  const std::vector<float> detail = use_detail ? MakeDetailImages(light_field, options) : std::vector<float>{};
  const float* centre = light_field.ViewData(shape.Centre());
  const float* centre_detail = use_detail ? DetailView(detail, shape, shape.Centre()) : nullptr;
  const std::vector<ViewPlan> plans = PlanViews(light_field, detail);
  const SplitTable splits = MakeSplitTable(plans);
  const float all_views = static_cast<float>(plans.size());
  const int tile_rows = std::max(1, options.tile_rows);
  const int tiles = (height + tile_rows - 1) / tile_rows;
  const std::size_t row_samples = static_cast<std::size_t>(width) * 3;

  CostVolume volume(width, height, labels);
#pragma omp parallel
  {
    // Per-thread scratch: one accumulator row set per sector for the tile, and one row of differences.
    std::vector<float> sector_sums(static_cast<std::size_t>(kSectors) * static_cast<std::size_t>(tile_rows) *
                                   static_cast<std::size_t>(width));
    std::vector<float> differences(row_samples);
    auto sector_row = [&](int sector, int row) {
      return sector_sums.data() +
             (static_cast<std::size_t>(sector) * static_cast<std::size_t>(tile_rows) + static_cast<std::size_t>(row)) *
                 static_cast<std::size_t>(width);
    };
#pragma omp for schedule(dynamic)
    for (int tile = 0; tile < tiles; ++tile) {
      const int y_begin = tile * tile_rows;
      const int y_end = std::min(height, y_begin + tile_rows);
      for (int l = 0; l < labels; ++l) {
        const float d = disparities[static_cast<std::size_t>(l)];
        std::fill(sector_sums.begin(), sector_sums.end(), 0.0f);
        for (const ViewPlan& plan : plans) {
          // DESIGN.md: the centre pixel (x, y) at disparity d is seen in view (u, v) at (x - du*d, y - dv*d).
          const float sx = -plan.du * d;
          const float sy = -plan.dv * d;
          for (int y = y_begin; y < y_end; ++y) {
            float* accumulator = sector_row(plan.sector, y - y_begin);
            if (use_detail) {
              AccumulateRowCost(plan.detail, 1, width, height, y, sx, sy,
                                centre_detail + static_cast<std::size_t>(y) * static_cast<std::size_t>(width), 0.0f,
                                options.detail_truncation, 1.0f, differences.data(), accumulator);
            }
            if (use_colour) {
              AccumulateRowCost(plan.colour, 3, width, height, y, sx, sy,
                                centre + static_cast<std::size_t>(y) * row_samples, options.colour_deadzone,
                                options.colour_truncation, options.colour_weight, differences.data(), accumulator);
            }
          }
        }
        for (int y = y_begin; y < y_end; ++y) {
          const unsigned char* candidate = occlusion ? occlusion->candidate.ptr<unsigned char>(y) : nullptr;
          const unsigned char* split = occlusion ? occlusion->split.ptr<unsigned char>(y) : nullptr;
          for (int x = 0; x < width; ++x) {
            std::array<float, kSectors> sums;
            float total = 0.0f;
            for (int s = 0; s < kSectors; ++s) {
              sums[s] = sector_row(s, y - y_begin)[x];
              total += sums[s];
            }
            float cost = total / all_views;
            if (candidate != nullptr && candidate[x] != 0 && splits.views_a[split[x]] > 0 &&
                splits.views_b[split[x]] > 0) {
              // Near an edge: the background is occluded in the views on the occluder's side, so keep the
              // better of the two halves split along the edge.
              const int j = split[x];
              float half_a = 0.0f;
              for (int s = 0; s < kSectors; ++s) half_a += splits.in_half_a[j][s] ? sums[s] : 0.0f;
              const float half_b = total - half_a;
              const float half = std::min(half_a / splits.views_a[j], half_b / splits.views_b[j]);
              cost = std::min(cost, options.half_patch_penalty * half);
            }
            volume.Curve(y, x)[l] = cost;
          }
        }
      }
    }
  }
  return volume;
}

void AggregateLocally(CostVolume& cost, const cv::Mat& guide_rgb, int radius, float epsilon) {
  if (radius <= 0) return;
  cv::Mat volume(cost.height(), cost.width(), CV_32FC(cost.labels()), cost.data());
  cv::Mat filtered;
  cv::ximgproc::guidedFilter(guide_rgb, volume, filtered, radius, epsilon);
  filtered.copyTo(volume);
}

}  // namespace lfsp::depth
