#include "lfsp/depth/cost_volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <string>
#include <utility>

#include "lfsp/core/conventions.h"
#include "lfsp/core/error.h"
#include "lfsp/depth/detail_weight.h"
#include "lfsp/depth/noise_matched_kernel.h"
#include "lfsp/depth/presmooth.h"

namespace lfsp::depth {
namespace {

// One non-centre view: where its samples are, how far it sits from the centre view, and its angular sector.
struct ViewPlan {
  const float* features;  // the view's feature rows: R, G, B (and detail), planar (FeatureImages)
  float du;               // u - uc
  float dv;               // v - vc
  int sector;
};

// Feature channels per pixel: R, G, B, and the detail image when the detail term has weight (without it, the
// colour alone: a quarter less to resample, which is most of the cost's time).
constexpr int kColourChannels = 3;
constexpr int kColourAndDetailChannels = 4;

// The per-view cost terms (CostOptions), as plain numbers for the inner loop.
struct TermWeights {
  std::array<float, 3> channel;  // weights of |dR|, |dG|, |dB|
  float colour_weight;
  float colour_deadzone;
  float colour_truncation;
  float detail_truncation;
  float detail_weight;
};

// How one view is resampled at one label's shift (sx, sy): the whole-pixel part and the weights of the taps on each
// axis. Bilinear uses taps 0 and 1 (weights 1 - a, a); noise-matched and cubic taps -1 .. 2 (NoiseMatchedWeights,
// CubicConvolutionWeights).
struct Taps {
  int ix;
  int iy;
  std::array<float, 4> wx;
  std::array<float, 4> wy;
};

Taps TapsFor(Sampler sampler, float sx, float sy) {
  const float fx = std::floor(sx);
  const float fy = std::floor(sy);
  const float ax = sx - fx;
  const float ay = sy - fy;
  Taps taps{static_cast<int>(fx), static_cast<int>(fy), {1.0f - ax, ax, 0.0f, 0.0f}, {1.0f - ay, ay, 0.0f, 0.0f}};
  if (sampler == Sampler::kNoiseMatched) {
    taps.wx = NoiseMatchedWeights(ax);
    taps.wy = NoiseMatchedWeights(ay);
  } else if (sampler == Sampler::kCubic) {
    taps.wx = CubicConvolutionWeights(ax);
    taps.wy = CubicConvolutionWeights(ay);
  }
  return taps;
}

// One pixel's cost from its feature differences |sample - centre| (CostOptions):
// colour_weight * min(max(wR |dR| + wG |dG| + wB |dB| - deadzone, 0), truncation)
// + detail_weight * min(|d detail|, truncation).
template <int kC>
[[gnu::always_inline]] inline float PixelCost(const float (&difference)[kC], const TermWeights& terms) {
  const float colour = std::min(std::max(terms.channel[0] * difference[0] + terms.channel[1] * difference[1] +
                                             terms.channel[2] * difference[2] - terms.colour_deadzone,
                                         0.0f),
                                terms.colour_truncation);
  float cost = terms.colour_weight * colour;
  if constexpr (kC > kColourChannels) cost += terms.detail_weight * std::min(difference[3], terms.detail_truncation);
  return cost;
}

// One view's feature row resampled at (x + sx, y + sy), compared with the centre view's feature row and turned into
// costs[x] (PixelCost). Rows are planar (FeatureImages): each channel's `width` samples in turn, so one loop over x
// resamples every channel and sums the pixel's cost, vectorised across pixels. Samples beyond the border are
// clamped. Built twice (AVX2 and generic) and chosen at run time.
//
// Bilinear: two taps per axis.
template <int kC>
__attribute__((target_clones("avx2", "default"))) void RowCostsBilinear(const float* view, int width, int height, int y,
                                                                        const Taps& taps, const float* centre_row,
                                                                        const TermWeights terms,
                                                                        float* __restrict costs) {
  const int ix = taps.ix;
  const int y0 = std::clamp(y + taps.iy, 0, height - 1);
  const int y1 = std::clamp(y + taps.iy + 1, 0, height - 1);
  const std::size_t stride = static_cast<std::size_t>(width) * kC;
  const float* row0 = view + static_cast<std::size_t>(y0) * stride;
  const float* row1 = view + static_cast<std::size_t>(y1) * stride;
  const float w00 = taps.wx[0] * taps.wy[0];
  const float w01 = taps.wx[1] * taps.wy[0];
  const float w10 = taps.wx[0] * taps.wy[1];
  const float w11 = taps.wx[1] * taps.wy[1];
  // The sample of channel c from its taps at columns c0 and c1 (c1 = c0 + 1 but where clamped).
  const auto sample = [&](int c, int c0, int c1) {
    const float* r0 = row0 + c * width;
    const float* r1 = row1 + c * width;
    return w00 * r0[c0] + w01 * r0[c1] + w10 * r1[c0] + w11 * r1[c1];
  };
  // Columns whose two taps are both inside the row: one vectorised loop.
  const int x_begin = std::clamp(-ix, 0, width);
  const int x_end = std::clamp(width - 1 - ix, x_begin, width);
  for (int x = x_begin; x < x_end; ++x) {
    float difference[kC];
    for (int c = 0; c < kC; ++c) difference[c] = std::abs(sample(c, x + ix, x + ix + 1) - centre_row[c * width + x]);
    costs[x] = PixelCost<kC>(difference, terms);
  }
  // The few columns near the border: clamp each tap.
  const auto clamped = [&](int x) {
    const int c0 = std::clamp(x + ix, 0, width - 1);
    const int c1 = std::clamp(x + ix + 1, 0, width - 1);
    float difference[kC];
    for (int c = 0; c < kC; ++c) difference[c] = std::abs(sample(c, c0, c1) - centre_row[c * width + x]);
    costs[x] = PixelCost<kC>(difference, terms);
  };
  for (int x = 0; x < x_begin; ++x) clamped(x);
  for (int x = x_end; x < width; ++x) clamped(x);
}

// Noise-matched or cubic (noise_matched_kernel.h): four taps per axis, separably: the four rows are mixed into
// `mixed` (kC * width floats of scratch), then four columns of that.
template <int kC>
__attribute__((target_clones("avx2", "default"))) void RowCostsFourTaps(const float* view, int width, int height, int y,
                                                                        const Taps& taps, const float* centre_row,
                                                                        const TermWeights terms,
                                                                        float* __restrict costs,
                                                                        float* __restrict mixed) {
  const std::array<float, 4>& wx = taps.wx;
  const std::array<float, 4>& wy = taps.wy;
  const int ix = taps.ix;
  const std::size_t stride = static_cast<std::size_t>(width) * kC;
  const auto row = [&](int k) {
    return view + static_cast<std::size_t>(std::clamp(y + taps.iy - 1 + k, 0, height - 1)) * stride;
  };
  {
    const float* __restrict r0 = row(0);
    const float* __restrict r1 = row(1);
    const float* __restrict r2 = row(2);
    const float* __restrict r3 = row(3);
    float* __restrict m = mixed;
    for (std::size_t p = 0; p < stride; ++p) m[p] = wy[0] * r0[p] + wy[1] * r1[p] + wy[2] * r2[p] + wy[3] * r3[p];
  }
  // Columns whose four taps are all inside the row.
  const int x_begin = std::clamp(1 - ix, 0, width);
  const int x_end = std::clamp(width - 2 - ix, x_begin, width);
  for (int x = x_begin; x < x_end; ++x) {
    float difference[kC];
    for (int c = 0; c < kC; ++c) {
      const float* m = mixed + c * width + x + ix;
      const float sample = wx[0] * m[-1] + wx[1] * m[0] + wx[2] * m[1] + wx[3] * m[2];
      difference[c] = std::abs(sample - centre_row[c * width + x]);
    }
    costs[x] = PixelCost<kC>(difference, terms);
  }
  const auto clamped = [&](int x) {
    float difference[kC];
    for (int c = 0; c < kC; ++c) {
      float sample = 0.0f;
      for (int k = 0; k < 4; ++k) sample += wx[k] * mixed[c * width + std::clamp(x + ix - 1 + k, 0, width - 1)];
      difference[c] = std::abs(sample - centre_row[c * width + x]);
    }
    costs[x] = PixelCost<kC>(difference, terms);
  };
  for (int x = 0; x < x_begin; ++x) clamped(x);
  for (int x = x_end; x < width; ++x) clamped(x);
}

// Adds one row's costs to total[x], to half_a[x] where in_half_a[x] is 1 (if half_a is not null), and to along[x]
// where in_along[x] is 1 (if along is not null).
__attribute__((target_clones("avx2", "default"))) void AccumulateRowCost(const float* __restrict cost, int width,
                                                                         float* total, const float* in_half_a,
                                                                         float* half_a, const float* in_along,
                                                                         float* along) {
  for (int x = 0; x < width; ++x) total[x] += cost[x];
  if (half_a != nullptr) {
    for (int x = 0; x < width; ++x) half_a[x] += cost[x] * in_half_a[x];
  }
  if (along != nullptr) {
    for (int x = 0; x < width; ++x) along[x] += cost[x] * in_along[x];
  }
}

// Where one row's costs are added (see AccumulateRowCost).
struct RowAccumulators {
  float* total;
  const float* in_half_a;
  float* half_a;
  const float* in_along;
  float* along;
};

// One view's cost at one label for one row, added to the tile's accumulators.
template <int kC>
void AddViewRow(bool four_taps, const float* view, int width, int height, int y, const Taps& taps,
                const float* centre_row, const TermWeights& terms, float* mixed, float* costs,
                const RowAccumulators& into) {
  if (four_taps) {
    RowCostsFourTaps<kC>(view, width, height, y, taps, centre_row, terms, costs, mixed);
  } else {
    RowCostsBilinear<kC>(view, width, height, y, taps, centre_row, terms, costs);
  }
  AccumulateRowCost(costs, width, into.total, into.in_half_a, into.half_a, into.in_along, into.along);
}

// Every view's features (`channels` of them), views in the light field's order, each view's rows planar: a row
// holds each channel's `width` samples in turn, so the cost's inner loop runs over contiguous pixels of each channel.
struct FeatureImages {
  int channels = kColourAndDetailChannels;
  std::vector<float> samples;

  const float* View(const LightFieldShape& shape, ViewIndex view) const {
    return samples.data() + static_cast<std::size_t>(CameraNumber(view, shape.nu)) * shape.ViewPixels() *
                                static_cast<std::size_t>(channels);
  }
};

// Channel c of a view stored with planar rows (`channels` channels), as a strided single-channel image.
cv::Mat PlanarChannel(const float* view, const LightFieldShape& shape, int channels, int c) {
  const std::size_t row_bytes =
      static_cast<std::size_t>(shape.width) * static_cast<std::size_t>(channels) * sizeof(float);
  return cv::Mat(shape.height, shape.width, CV_32F,
                 const_cast<float*>(view) + static_cast<std::ptrdiff_t>(c) * shape.width, row_bytes);
}

// Copies the channels of `sources` (in order) into the planar rows of `view`.
void StorePlanar(const std::vector<cv::Mat>& sources, float* view, const LightFieldShape& shape, int channels) {
  std::vector<cv::Mat> planes;
  std::vector<int> from_to;
  for (int c = 0; c < channels; ++c) {
    planes.push_back(PlanarChannel(view, shape, channels, c));
    from_to.insert(from_to.end(), {c, c});
  }
  cv::mixChannels(sources, planes, from_to);
}

// The centre view's features as the noise-matched sampler compares them: blurred by kNoiseMatchedCentreKernel.
// Filtered interleaved, as a `channels`-channel image: OpenCV's filters round a single-channel image's last columns
// differently, so planes filtered one by one would change the costs in the last bits.
std::vector<float> NoiseMatchedCentre(const FeatureImages& features, const LightFieldShape& shape) {
  const int channels = features.channels;
  const float* centre = features.View(shape, shape.Centre());
  std::vector<cv::Mat> planes;
  for (int c = 0; c < channels; ++c) planes.push_back(PlanarChannel(centre, shape, channels, c));
  cv::Mat interleaved;
  cv::merge(planes, interleaved);
  const cv::Mat kernel(3, 1, CV_32F, const_cast<float*>(kNoiseMatchedCentreKernel.data()));
  // Replicated borders, as the resampled views clamp their taps.
  cv::sepFilter2D(interleaved, interleaved, CV_32F, kernel, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  std::vector<float> blurred(shape.ViewPixels() * static_cast<std::size_t>(channels));
  StorePlanar({interleaved}, blurred.data(), shape, channels);
  return blurred;
}

// Every view's features: its RGB (presmoothed when CostOptions::presmooth_sigma asks) and, when `with_detail`, its
// detail image: the high-pass grey image (mean of RGB; the colour of faint texture adds little, measured), optionally
// divided by its local RMS.
FeatureImages MakeFeatureImages(const LightField& light_field, const CostOptions& options, bool with_detail) {
  const LightFieldShape& shape = light_field.shape();
  FeatureImages features;
  features.channels = with_detail ? kColourAndDetailChannels : kColourChannels;
  const std::size_t view_samples = shape.ViewPixels() * static_cast<std::size_t>(features.channels);
  features.samples.resize(shape.Views() * view_samples);
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < views; ++i) {
    float* target = features.samples.data() + static_cast<std::size_t>(i) * view_samples;
    cv::Mat rgb = light_field.View(ViewFromCameraNumber(i, shape.nu));
    if (options.presmooth_sigma > 0.0) {
      cv::Mat smoothed;
      PresmoothView(rgb, options.presmooth_sigma, smoothed);
      rgb = smoothed;
    }
    if (!with_detail) {
      StorePlanar({rgb}, target, shape, features.channels);
      continue;
    }
    cv::Mat detail = DetailHighPass(rgb, options.detail_sigma);
    if (options.detail_normalise_sigma > 0.0f) {
      cv::Mat energy;
      cv::multiply(detail, detail, energy);
      cv::GaussianBlur(energy, energy, cv::Size(), options.detail_normalise_sigma, options.detail_normalise_sigma,
                       cv::BORDER_REFLECT);
      cv::sqrt(energy, energy);
      energy += options.detail_normalise_epsilon;
      cv::divide(detail, energy, detail);
    }
    StorePlanar({rgb, detail}, target, shape, features.channels);
  }
  return features;
}

std::vector<ViewPlan> PlanViews(const LightFieldShape& shape, const FeatureImages& features, int skip_ring) {
  const ViewIndex centre = shape.Centre();
  std::vector<ViewPlan> plans;
  for (int v = 0; v < shape.nv; ++v) {
    for (int u = 0; u < shape.nu; ++u) {
      if (std::max(std::abs(u - centre.u), std::abs(v - centre.v)) <= skip_ring) continue;
      plans.push_back({features.View(shape, {u, v}), static_cast<float>(u - centre.u), static_cast<float>(v - centre.v),
                       SectorOfOffset(u - centre.u, v - centre.v)});
    }
  }
  return plans;
}

// Which sectors form half A of each split (half B is the complement), and how many views each half holds.
struct SplitTable {
  std::array<std::array<bool, kSectors>, kSplits> in_half_a{};
  std::array<float, kSplits> views_a{};
  std::array<float, kSplits> views_b{};
  // Per AlongPairForEdgeNormal pair a: whether sector s is a or a + kSectors/2, and how many views those hold.
  std::array<std::array<bool, kSectors>, kSectors / 2> along_edge{};
  std::array<float, kSectors / 2> views_along{};
};

SplitTable MakeSplitTable(const std::vector<ViewPlan>& plans) {
  SplitTable table;
  for (int j = 0; j < kSplits; ++j) {
    for (int k = 0; k < kSectors / 2; ++k) table.in_half_a[j][(j + k) % kSectors] = true;
    for (const ViewPlan& plan : plans) (table.in_half_a[j][plan.sector] ? table.views_a[j] : table.views_b[j]) += 1;
  }
  for (int a = 0; a < kSectors / 2; ++a) {
    table.along_edge[a][a] = table.along_edge[a][a + kSectors / 2] = true;
    for (const ViewPlan& plan : plans) table.views_along[a] += table.along_edge[a][plan.sector] ? 1.0f : 0.0f;
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

std::string SamplerName(Sampler sampler) {
  switch (sampler) {
    case Sampler::kBilinear:
      return "bilinear";
    case Sampler::kNoiseMatched:
      return "noise-matched";
    case Sampler::kCubic:
      return "cubic";
    case Sampler::kAutomatic:
      break;
  }
  return "automatic";
}

Sampler SamplerFromString(const std::string& name) {
  for (const Sampler sampler : {Sampler::kAutomatic, Sampler::kBilinear, Sampler::kNoiseMatched, Sampler::kCubic})
    if (name == SamplerName(sampler)) return sampler;
  throw Error("sampler '" + name + "': unknown (expected automatic, bilinear, noise-matched or cubic)");
}

std::vector<float> LabelDisparities(float min, float max, int count) {
  if (count < 3)
    throw Error("depth: " + OptionName("labels") + " must be at least 3 (got " + std::to_string(count) + ")");
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

float CostRange(const CostOptions& options) {
  const float detail_weight = options.detail_weight < 0.0f ? 1.0f : options.detail_weight;
  const float detail = options.detail_sigma > 0.0f ? detail_weight * options.detail_truncation : 0.0f;
  return options.colour_weight * options.colour_truncation + detail;
}

namespace {

// Which part of the angular patch may stand in for the whole one at a pixel near an edge (the split's two halves).
enum class HalfChoice { kNone, kHalfA, kHalfB, kLowerEnvelope };

// An occluder hides the background in the views on its side of the edge only, so the two halves then prefer
// different labels, and the one whose best label costs less is the one that sees the pixel.
// `side_costs(l)` gives the two halves' mean costs at label l.
template <typename SideCosts>
HalfChoice ChooseHalf(int labels, int agree_labels, const SideCosts& side_costs) {
  if (agree_labels < 0) return HalfChoice::kLowerEnvelope;
  float best_a = std::numeric_limits<float>::infinity(), best_b = best_a;
  int label_a = 0, label_b = 0;
  for (int l = 0; l < labels; ++l) {
    const auto [a, b] = side_costs(l);
    if (a < best_a) best_a = a, label_a = l;
    if (b < best_b) best_b = b, label_b = l;
  }
  if (std::abs(label_a - label_b) <= agree_labels) return HalfChoice::kNone;
  return best_a <= best_b ? HalfChoice::kHalfA : HalfChoice::kHalfB;
}

// The chosen half's cost at one label, times `penalty`; infinite where no half may stand in.
float HalfCost(HalfChoice choice, float side_a, float side_b, float penalty) {
  switch (choice) {
    case HalfChoice::kHalfA:
      return penalty * side_a;
    case HalfChoice::kHalfB:
      return penalty * side_b;
    case HalfChoice::kLowerEnvelope:
      return penalty * std::min(side_a, side_b);
    case HalfChoice::kNone:
      break;
  }
  return std::numeric_limits<float>::infinity();
}

}  // namespace

CostVolume BuildCostVolume(const LightField& light_field, const std::vector<float>& disparities,
                           const CostOptions& options, const OcclusionMap* occlusion,
                           OcclusionAlternatives* alternatives) {
  CheckInput(light_field, disparities, occlusion);
  const LightFieldShape& shape = light_field.shape();
  const int width = shape.width;
  const int height = shape.height;
  const int labels = static_cast<int>(disparities.size());
  std::array<float, 3> channel = options.channel_weights;
  if (channel[0] < 0.0f) channel = {1.0f, 1.0f, 1.0f};
  const TermWeights terms{channel,
                          options.colour_weight,
                          options.colour_deadzone,
                          options.colour_truncation,
                          options.detail_sigma > 0.0f ? options.detail_truncation : 0.0f,
                          options.detail_weight < 0.0f ? 1.0f : options.detail_weight};
  const bool with_detail = options.detail_sigma > 0.0f && terms.detail_weight > 0.0f;
  if (!with_detail && !(options.colour_weight > 0.0f)) {
    throw Error("depth: the cost needs the detail or the colour term, and both have no weight (" +
                OptionName("colour_weight") + " 0, detail weight 0: give " + OptionName("detail_weight") + ")");
  }
  const FeatureImages features = MakeFeatureImages(light_field, options, with_detail);
  const bool noise_matched = options.sampler == Sampler::kNoiseMatched;
  const bool four_taps = noise_matched || options.sampler == Sampler::kCubic;
  const std::vector<float> blurred_centre = noise_matched ? NoiseMatchedCentre(features, shape) : std::vector<float>();
  const float* centre = noise_matched ? blurred_centre.data() : features.View(shape, shape.Centre());
  const auto add_view_row =
      features.channels == kColourChannels ? AddViewRow<kColourChannels> : AddViewRow<kColourAndDetailChannels>;
  const std::vector<ViewPlan> plans = PlanViews(shape, features, std::max(0, options.excluded_ring));
  if (plans.empty())
    throw Error("depth: excluding the views within " + std::to_string(options.excluded_ring) +
                " of the centre leaves none");
  const SplitTable splits = MakeSplitTable(plans);
  const float all_views = static_cast<float>(plans.size());
  const int tile_rows = std::max(1, options.tile_rows);
  const int tiles = (height + tile_rows - 1) / tile_rows;
  const std::size_t row_samples = static_cast<std::size_t>(width) * static_cast<std::size_t>(features.channels);

  CostVolume volume(width, height, labels);
  if (alternatives != nullptr) {
    constexpr float kNone = std::numeric_limits<float>::infinity();
    alternatives->half = CostVolume(width, height, labels, kNone);
    alternatives->along = CostVolume(width, height, labels, kNone);
  }
#pragma omp parallel
  {
    // Per-thread scratch for one tile: per label and row, the sum over all views and over the views in half A of
    // each pixel's split; per sector and row, whether that sector lies in half A of the pixel's split (0/1).
    // Views are the outer loop, so each view's rows for the tile stay in cache across all labels.
    const std::size_t tile_size = static_cast<std::size_t>(tile_rows) * static_cast<std::size_t>(width);
    std::vector<float> totals(static_cast<std::size_t>(labels) * tile_size);
    std::vector<float> halves(occlusion ? totals.size() : 0);
    std::vector<float> in_half_a(occlusion ? static_cast<std::size_t>(kSectors) * tile_size : 0);
    // The same for the views along each pixel's edge (the pair of opposite sectors nearest its direction).
    const bool along_edge = occlusion && options.along_edge_penalty > 0.0f;
    std::vector<float> alongs(along_edge ? totals.size() : 0);
    std::vector<float> in_along(along_edge ? static_cast<std::size_t>(kSectors) * tile_size : 0);
    std::vector<float> costs(static_cast<std::size_t>(width));
    std::vector<float> mixed(four_taps ? row_samples : 0);
    auto row_of = [&](std::vector<float>& buffer, int index, int row) {
      return buffer.data() + static_cast<std::size_t>(index) * tile_size +
             static_cast<std::size_t>(row) * static_cast<std::size_t>(width);
    };
#pragma omp for schedule(dynamic)
    for (int tile = 0; tile < tiles; ++tile) {
      const int y_begin = tile * tile_rows;
      const int y_end = std::min(height, y_begin + tile_rows);
      std::fill(totals.begin(), totals.end(), 0.0f);
      std::fill(halves.begin(), halves.end(), 0.0f);
      std::fill(alongs.begin(), alongs.end(), 0.0f);
      if (occlusion) {
        for (int y = y_begin; y < y_end; ++y) {
          const unsigned char* split = occlusion->split.ptr<unsigned char>(y);
          for (int s = 0; s < kSectors; ++s) {
            float* mask = row_of(in_half_a, s, y - y_begin);
            for (int x = 0; x < width; ++x) mask[x] = splits.in_half_a[split[x]][s] ? 1.0f : 0.0f;
            if (along_edge) {
              float* along_mask = row_of(in_along, s, y - y_begin);
              const unsigned char* along = occlusion->along.ptr<unsigned char>(y);
              for (int x = 0; x < width; ++x) along_mask[x] = splits.along_edge[along[x]][s] ? 1.0f : 0.0f;
            }
          }
        }
      }
      for (const ViewPlan& plan : plans) {
        for (int l = 0; l < labels; ++l) {
          // docs/DESIGN.md: the centre pixel (x, y) at disparity d is seen in view (u, v) at (x - du*d, y - dv*d).
          const float d = disparities[static_cast<std::size_t>(l)];
          const Taps taps = TapsFor(options.sampler, -plan.du * d, -plan.dv * d);
          for (int y = y_begin; y < y_end; ++y) {
            const int row = y - y_begin;
            const float* centre_row = centre + static_cast<std::size_t>(y) * row_samples;
            add_view_row(four_taps, plan.features, width, height, y, taps, centre_row, terms, mixed.data(),
                         costs.data(),
                         {row_of(totals, l, row), occlusion ? row_of(in_half_a, plan.sector, row) : nullptr,
                          occlusion ? row_of(halves, l, row) : nullptr,
                          along_edge ? row_of(in_along, plan.sector, row) : nullptr,
                          along_edge ? row_of(alongs, l, row) : nullptr});
          }
        }
      }
      for (int y = y_begin; y < y_end; ++y) {
        const int row = y - y_begin;
        const unsigned char* candidate = occlusion ? occlusion->candidate.ptr<unsigned char>(y) : nullptr;
        const unsigned char* split = occlusion ? occlusion->split.ptr<unsigned char>(y) : nullptr;
        const unsigned char* along_pair = occlusion ? occlusion->along.ptr<unsigned char>(y) : nullptr;
        for (int x = 0; x < width; ++x) {
          float* curve = volume.Curve(y, x);
          const bool use_halves =
              candidate != nullptr && candidate[x] != 0 && splits.views_a[split[x]] > 0 && splits.views_b[split[x]] > 0;
          float* half_curve = use_halves && alternatives ? alternatives->half.Curve(y, x) : nullptr;
          float* along_curve = use_halves && alternatives ? alternatives->along.Curve(y, x) : nullptr;
          const auto side_costs = [&](int l) {
            const int j = split[x];
            const float total = row_of(totals, l, row)[x];
            const float half_a = row_of(halves, l, row)[x];
            return std::pair<float, float>(half_a / splits.views_a[j], (total - half_a) / splits.views_b[j]);
          };
          const HalfChoice choice =
              use_halves ? ChooseHalf(labels, options.halves_agree_labels, side_costs) : HalfChoice::kNone;
          for (int l = 0; l < labels; ++l) {
            const float total = row_of(totals, l, row)[x];
            float cost = total / all_views;
            if (use_halves) {
              // Near an edge: the background is occluded in the views on the occluder's side, so the half split
              // along the edge that sees the pixel may replace the whole patch (ChooseHalf).
              const auto [side_a, side_b] = side_costs(l);
              const float half = HalfCost(choice, side_a, side_b, options.half_patch_penalty);
              if (half_curve) half_curve[l] = half;
              if (!alternatives) cost = std::min(cost, half);
              // In a gap between two occluders (a comb's teeth, a fence) both halves hold an occluder, but the
              // views along the edge see through the gap.
              const int a = along_pair[x];
              if (along_edge && splits.views_along[a] > 0) {
                const float along = options.along_edge_penalty * row_of(alongs, l, row)[x] / splits.views_along[a];
                if (along_curve) along_curve[l] = along;
                if (!alternatives) cost = std::min(cost, along);
              }
            }
            curve[l] = cost;
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
