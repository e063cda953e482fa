// A white image estimated from the capture itself, for raws that come without one.
//
// Every micro-image is the same vignetting profile (the image of the main-lens exit pupil through one micro-lens)
// times the scene it sees. Dividing each micro-image by its own brightness, per Bayer phase (so the scene's
// brightness and colour go), and averaging over thousands of lenses by offset from the lens centre leaves the
// profile: the scene inside the micro-images differs from lens to lens and averages out, and lens centres fall at
// every sub-pixel phase, so the offsets are sampled finely. What a single capture cannot show is the smooth
// main-lens falloff across the sensor (it is indistinguishable from the scene's own brightness): the estimate leaves
// it in the light field.
//
// The estimate must be right to a few parts in a thousand from one offset to the next, not only on average: its
// error repeats in every micro-image, so each view inherits it as a pattern tied to the lens lattice, the same in
// every view, and a view-invariant pattern reads as texture at disparity 0. On the full-size F01 two-horses capture
// without noise, the first version of this estimate (0.25 px bins, each lens divided by its plain core mean) put
// the background's disparity 0.17 px off and depth's BadPix 0.07 at 80 % (3.2 % with the true white image). Two
// things made it so, each measured against the simulator's own white image:
// - The brightness a lens is divided by. A plain mean over the core mixes offsets that depend on where the lens
//   centre falls between pixels, so lenses at one sub-pixel phase were divided by a dimmer mean than others. As
//   every offset bin is filled by lenses of one phase, that came back as a +-3 % ripple with a period of one and two
//   pixels in the profile. A first pass estimates the profile; the second divides each lens by its least-squares
//   fit to that profile, smoothed well beyond a pixel so that the ripple cannot feed itself back.
// - Blur. 0.25 px bins smoothed by 0.25 px rounded the micro-image's steep edge: 7 % too bright at 4.5-5 px from
//   the centre, 35 % at 5-5.5 px. The whole sensor's lenses now fill 0.1 px bins smoothed by 0.05 px, and each tile
//   of the sensor (the micro-image changes shape towards the corners of real cameras) only scales that profile by
//   a smooth even low-order surface fitted to its own coarse profile: a full profile per tile was noise at this
//   resolution.
// On a hexagonal lattice the shifted and the unshifted lens rows each get their own profile as well (kRowKinds).

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "bayer_preprocess.h"
#include "lattice.h"
#include "lfsp/core/error.h"
#include "lfsp/core/ordered_reduction.h"
#include "lfsp/core/rounding.h"
#include "lfsp/decode/lenslet_decoder.h"

namespace lfsp::decode {
namespace {

constexpr double kBinPixels = 0.1;  // profile bin size
// Smoothing of the whole sensor's binned profile (Gaussian sigma, px): little enough to keep the micro-image's soft
// edge (the sensor's ~10^5 lenses put about a thousand samples in every bin).
constexpr double kProfileSmoothPixels = 0.05;
// Smoothing of a tile's profile and of the whole sensor's before their ratio is fitted (px).
constexpr double kTileSmoothPixels = 0.5;
// Smoothing of the first pass's profile when each lens is fitted to it (px): removes any ripple with a period of
// one or two pixels (its amplitude falls by exp(-2 pi^2 sigma^2 / period^2) < 1e-9), so that no lens's brightness
// depends on where its centre falls between pixels through the ripple. The smoothed profile is flatter than the true
// one over the core; that changes every lens's fitted brightness alike (to first order), which the second pass's
// ratio of sums absorbs.
constexpr double kGainProfileSmoothPixels = 3.0;
constexpr double kCoreFraction = 0.3;    // core radius (fitted brightness) as a fraction of the spacing
constexpr double kReachFraction = 0.62;  // profile radius: beyond the hexagonal cell's corner (spacing / sqrt(3))
constexpr float kSaturated = 0.98f;      // levelled value from which a pixel counts as clipped
constexpr double kWhiteLevel = 0.6;      // the synthetic white's core level, as a fraction of the raw range
// Where the whole sensor's coarse profile is above this fraction of its peak, the micro-image counts as lit: only there
// are a tile's and a kind of row's profiles compared with it.
constexpr double kLitFraction = 0.2;

// The sensor's response per Bayer phase relative to green: normalizedResponses when the metadata has them, else
// the inverse of the white-balance gains, else flat.
std::array<double, 4> PhaseResponse(const LytroMetadata& metadata, BayerPattern pattern) {
  const std::array<int, 4> tile = TileChannels(pattern);
  std::array<double, 4> response = {1.0, 1.0, 1.0, 1.0};
  if (const auto& r = metadata.colour.normalized_response; r && r->r > 0 && r->gr > 0 && r->gb > 0 && r->b > 0) {
    for (int phase = 0; phase < 4; ++phase)
      response[static_cast<std::size_t>(phase)] = Channel(*r, tile[static_cast<std::size_t>(phase)]) / r->gr;
  } else if (const auto& g = metadata.colour.white_balance_gain; g && g->r > 0 && g->gr > 0 && g->gb > 0 && g->b > 0) {
    for (int phase = 0; phase < 4; ++phase)
      response[static_cast<std::size_t>(phase)] = g->gr / Channel(*g, tile[static_cast<std::size_t>(phase)]);
  }
  return response;
}

// The hexagonal lattice's two kinds of lens rows, unshifted and shifted by half a pitch (HexLattice::Shift). On the
// real F01 frames their micro-images differ: at 0.4 spacings (4 px) along the row, relative to their centres, the
// shifted rows' are 1.1-1.3 % brighter than the unshifted rows' (IMG_1-3; alike in every ninth of the sensor on IMG_1
// and IMG_2), where the simulator's are the same. One profile for both left that difference in the views as rows
// alternating in brightness, 7-9 times stronger in the outermost views than in the centre one (BENCHMARKS.md,
// thirty-ninth session). Each kind of row gets its own ratio to the whole profile.
constexpr int kRowKinds = 2;

// Per offset bin, tile and kind of row: the sum of pixel values and the sum of the brightness of the lenses they
// came from (their ratio is the profile).
struct ProfileAccumulator {
  int bins = 0;   // per axis
  int tiles = 0;  // per axis
  std::vector<double> sum;
  std::vector<double> weight;
  ProfileAccumulator(int bins_per_axis, int tiles_per_axis)
      : bins(bins_per_axis),
        tiles(tiles_per_axis),
        sum(static_cast<std::size_t>(bins_per_axis) * static_cast<std::size_t>(bins_per_axis) *
                static_cast<std::size_t>(tiles_per_axis) * static_cast<std::size_t>(tiles_per_axis) * kRowKinds,
            0.0),
        weight(sum.size(), 0.0) {}
  std::size_t Index(int tile, int row_kind, int by, int bx) const {
    return ((static_cast<std::size_t>(tile) * kRowKinds + static_cast<std::size_t>(row_kind)) * bins + by) * bins + bx;
  }
  void Merge(const ProfileAccumulator& other) {
    for (std::size_t n = 0; n < sum.size(); ++n) {
      sum[n] += other.sum[n];
      weight[n] += other.weight[n];
    }
  }
};

[[gnu::always_inline]] inline float Bilinear(const cv::Mat& profile, double fx, double fy) {
  const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= profile.cols || y0 + 1 >= profile.rows) return 0.0f;
  const auto ax = static_cast<float>(fx - x0), ay = static_cast<float>(fy - y0);
  const float* r0 = profile.ptr<float>(y0);
  const float* r1 = profile.ptr<float>(y0 + 1);
  return (1 - ay) * ((1 - ax) * r0[x0] + ax * r0[x0 + 1]) + ay * ((1 - ax) * r1[x0] + ax * r1[x0 + 1]);
}

// Adds one lens's micro-image (of a `tile` and a `row_kind`); false (nothing added) when it is clipped, off the sensor
// or has an empty phase. The lens's brightness per Bayer phase is its core's least-squares scale of `first_pass` (a
// profile on the accumulator's bins), or the core's plain mean without one. Built twice (AVX2 and generic) and chosen
// at run time: with SSE4.1 and later the profile lookup's floor is an instruction instead of a library call.
__attribute__((target_clones("avx2", "default"))) bool AddLens(const cv::Mat& levelled, double cx, double cy,
                                                               double reach, double core, int tile, int row_kind,
                                                               const cv::Mat* first_pass,
                                                               ProfileAccumulator& accumulator) {
  const int x0 = static_cast<int>(std::floor(cx - reach)), x1 = static_cast<int>(std::ceil(cx + reach));
  const int y0 = static_cast<int>(std::floor(cy - reach)), y1 = static_cast<int>(std::ceil(cy + reach));
  if (x0 < 0 || y0 < 0 || x1 >= levelled.cols || y1 >= levelled.rows) return false;
  const double half = 0.5 * (accumulator.bins - 1);
  std::array<double, 4> core_sum{};
  std::array<double, 4> core_norm{};
  for (int y = y0; y <= y1; ++y) {
    const float* row = levelled.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      if (r2 > reach * reach) continue;
      if (row[x] >= kSaturated) return false;
      if (r2 <= core * core) {
        const double v =
            first_pass ? Bilinear(*first_pass, (x - cx) / kBinPixels + half, (y - cy) / kBinPixels + half) : 1.0;
        core_sum[static_cast<std::size_t>(BayerPhase(x, y))] += row[x] * v;
        core_norm[static_cast<std::size_t>(BayerPhase(x, y))] += v * v;
      }
    }
  }
  std::array<double, 4> brightness{};
  for (std::size_t phase = 0; phase < 4; ++phase) {
    if (!(core_norm[phase] > 0.0) || !(core_sum[phase] > 0.0)) return false;
    brightness[phase] = core_sum[phase] / core_norm[phase];
  }
  for (int y = y0; y <= y1; ++y) {
    const float* row = levelled.ptr<float>(y);
    for (int x = x0; x <= x1; ++x) {
      const double dx = x - cx, dy = y - cy;
      if (dx * dx + dy * dy > reach * reach) continue;
      const int bx = RoundHalfAway(dx / kBinPixels + half);
      const int by = RoundHalfAway(dy / kBinPixels + half);
      if (bx < 0 || by < 0 || bx >= accumulator.bins || by >= accumulator.bins) continue;
      const std::size_t n = accumulator.Index(tile, row_kind, by, bx);
      // Sums, not a mean of ratios: a dim lens beside a bright one (whose light reaches the cell's edge) would
      // otherwise weigh as much as any other.
      accumulator.sum[n] += row[x];
      accumulator.weight[n] += brightness[static_cast<std::size_t>(BayerPhase(x, y))];
    }
  }
  return true;
}

cv::Mat BinsToMat(const double* data, int bins) {
  cv::Mat m(bins, bins, CV_64F);
  std::copy(data, data + static_cast<std::size_t>(bins) * static_cast<std::size_t>(bins), m.ptr<double>());
  return m;
}

cv::Mat Blur(const cv::Mat& m, double sigma_pixels) {
  cv::Mat out;
  cv::GaussianBlur(m, out, cv::Size(0, 0), sigma_pixels / kBinPixels, 0.0, cv::BORDER_CONSTANT);
  return out;
}

// Normalised convolution: the profile from its smoothed sums (0 where no lens reached).
cv::Mat SmoothedProfile(const cv::Mat& sum, const cv::Mat& weight, double sigma_pixels) {
  const cv::Mat s = Blur(sum, sigma_pixels), w = Blur(weight, sigma_pixels);
  cv::Mat profile(sum.size(), CV_64F);
  for (int y = 0; y < sum.rows; ++y)
    for (int x = 0; x < sum.cols; ++x)
      profile.at<double>(y, x) = w.at<double>(y, x) > 1e-9 ? s.at<double>(y, x) / w.at<double>(y, x) : 0.0;
  return profile;
}

// The even low-order surface c0 + c1 x^2 + c2 y^2 + c3 x y (x, y: offset in px) that a tile's profile is of the
// whole sensor's, fitted (weighted by the tile's samples) where the micro-image is lit: the level and elongation by
// which real micro-images change towards the sensor's corners, in four numbers that thousands of lenses pin down (a
// tile's own profile at 0.1 px bins would be noise). No odd (tilt) terms: a tilt makes opposite views differ in
// brightness, which depth reads as a shift. The tilt one capture can measure per tile was noise on the simulator
// (about 3e-4 per px), yet it took full-size two-horses depth without a white image from 13.3 to 19.6 % BadPix 0.07
// (F01) and from 4.1 to 6.4 % (Illum); on the real F01 frame IMG_1 it changed how much the outer views' brightness
// relative to the centre view varies across the image (p95/p5, five views) by at most 0.6 %.
using TileCorrection = cv::Vec<double, 4>;
TileCorrection NoCorrection() { return TileCorrection(1.0, 0.0, 0.0, 0.0); }

TileCorrection CorrectionBasis(double ox, double oy) { return TileCorrection(1.0, ox * ox, oy * oy, ox * oy); }

// `lit_level`: the level of `whole_coarse` above which the micro-image counts as lit (kLitFraction of its peak).
TileCorrection FitTileCorrection(const cv::Mat& tile_sum, const cv::Mat& tile_weight, const cv::Mat& whole_coarse,
                                 double lit_level) {
  const cv::Mat tile = SmoothedProfile(tile_sum, tile_weight, kTileSmoothPixels);
  const cv::Mat weight = Blur(tile_weight, kTileSmoothPixels);
  const double centre = 0.5 * (tile.cols - 1);
  cv::Matx44d normal = cv::Matx44d::zeros();
  TileCorrection right = TileCorrection::all(0.0);
  for (int y = 0; y < tile.rows; ++y)
    for (int x = 0; x < tile.cols; ++x) {
      const double whole = whole_coarse.at<double>(y, x), w = weight.at<double>(y, x);
      if (whole < lit_level || !(w > 0.0)) continue;
      const TileCorrection basis = CorrectionBasis((x - centre) * kBinPixels, (y - centre) * kBinPixels);
      right += w * (tile.at<double>(y, x) / whole) * basis;
      normal += w * basis * basis.t();
    }
  TileCorrection solution;
  if (!cv::solve(normal, right, solution, cv::DECOMP_CHOLESKY)) return NoCorrection();
  return solution;
}

// Every tile's profile for each kind of row, indexed tile * kRowKinds + kind: the whole sensor's (normalised
// convolution of all the sums, kProfileSmoothPixels) times the tile's low-order correction (both kinds of row
// together; tiles with too few lenses take none) times the kind of row's profile over the whole sensor's, both
// smoothed like a tile's (kTileSmoothPixels: half the sensor's lenses make each, so the ratio needs no low-order
// model; on the simulator it stays within 1e-4 of 1). `row_kind_ratios`, if given, receives those two ratios.
std::vector<cv::Mat> TileProfiles(const ProfileAccumulator& accumulator,
                                  std::array<cv::Mat, kRowKinds>* row_kind_ratios = nullptr) {
  const int bins = accumulator.bins, tiles = accumulator.tiles;
  const auto bins_of = [&](const std::vector<double>& values, int tile, int kind) {
    return BinsToMat(&values[accumulator.Index(tile, kind, 0, 0)], bins);
  };
  cv::Mat whole_sum = cv::Mat::zeros(bins, bins, CV_64F), whole_weight = cv::Mat::zeros(bins, bins, CV_64F);
  std::vector<cv::Mat> sums(static_cast<std::size_t>(tiles * tiles)), weights(sums.size());
  std::array<cv::Mat, kRowKinds> kind_sums, kind_weights;
  for (int kind = 0; kind < kRowKinds; ++kind) {
    kind_sums[static_cast<std::size_t>(kind)] = cv::Mat::zeros(bins, bins, CV_64F);
    kind_weights[static_cast<std::size_t>(kind)] = cv::Mat::zeros(bins, bins, CV_64F);
  }
  for (int t = 0; t < tiles * tiles; ++t) {
    const auto k = static_cast<std::size_t>(t);
    sums[k] = cv::Mat::zeros(bins, bins, CV_64F);
    weights[k] = cv::Mat::zeros(bins, bins, CV_64F);
    for (int kind = 0; kind < kRowKinds; ++kind) {
      const cv::Mat sum = bins_of(accumulator.sum, t, kind), weight = bins_of(accumulator.weight, t, kind);
      sums[k] += sum;
      weights[k] += weight;
      kind_sums[static_cast<std::size_t>(kind)] += sum;
      kind_weights[static_cast<std::size_t>(kind)] += weight;
    }
    whole_sum += sums[k];
    whole_weight += weights[k];
  }
  const cv::Mat whole_coarse = SmoothedProfile(whole_sum, whole_weight, kTileSmoothPixels);
  const cv::Mat fine = SmoothedProfile(whole_sum, whole_weight, kProfileSmoothPixels);
  const double median_weight = [&] {
    std::vector<double> totals;
    for (const cv::Mat& w : weights) totals.push_back(cv::sum(w)[0]);
    std::nth_element(totals.begin(), totals.begin() + static_cast<std::ptrdiff_t>(totals.size() / 2), totals.end());
    return totals[totals.size() / 2];
  }();
  // Each kind of row's profile over the whole sensor's, smoothed like a tile's (kTileSmoothPixels), where the
  // micro-image is lit (1 elsewhere).
  double peak = 0.0;
  cv::minMaxLoc(whole_coarse, nullptr, &peak);
  const double lit_level = kLitFraction * peak;
  // A kind with few of the lenses (a capture a few rows high, whose other rows fall off the sensor) keeps the whole
  // profile, as a sparse tile does.
  const double whole_total = cv::sum(whole_weight)[0];
  std::array<cv::Mat, kRowKinds> kind_ratio;
  for (std::size_t kind = 0; kind < kRowKinds; ++kind) {
    kind_ratio[kind] = cv::Mat::ones(bins, bins, CV_64F);
    if (cv::sum(kind_weights[kind])[0] < 0.25 * whole_total / kRowKinds) continue;
    const cv::Mat coarse = SmoothedProfile(kind_sums[kind], kind_weights[kind], kTileSmoothPixels);
    for (int y = 0; y < bins; ++y)
      for (int x = 0; x < bins; ++x)
        if (whole_coarse.at<double>(y, x) > lit_level)
          kind_ratio[kind].at<double>(y, x) = coarse.at<double>(y, x) / whole_coarse.at<double>(y, x);
  }
  const double centre = 0.5 * (bins - 1);
  std::vector<cv::Mat> profiles;
  for (int t = 0; t < tiles * tiles; ++t) {
    const auto k = static_cast<std::size_t>(t);
    const bool sparse = cv::sum(weights[k])[0] < 0.25 * median_weight;
    const TileCorrection c = sparse ? NoCorrection() : FitTileCorrection(sums[k], weights[k], whole_coarse, lit_level);
    for (const cv::Mat& ratio : kind_ratio) {
      cv::Mat profile(bins, bins, CV_32F);
      for (int y = 0; y < bins; ++y)
        for (int x = 0; x < bins; ++x) {
          const double scale = c.dot(CorrectionBasis((x - centre) * kBinPixels, (y - centre) * kBinPixels));
          profile.at<float>(y, x) = static_cast<float>(fine.at<double>(y, x) * scale * ratio.at<double>(y, x));
        }
      profiles.push_back(profile);
    }
  }
  if (row_kind_ratios) *row_kind_ratios = kind_ratio;
  return profiles;
}

// The first pass's profiles smoothed for fitting each lens's brightness to them (kGainProfileSmoothPixels).
std::vector<cv::Mat> GainProfiles(std::vector<cv::Mat> profiles) {
  for (cv::Mat& p : profiles)
    cv::GaussianBlur(p, p, cv::Size(0, 0), kGainProfileSmoothPixels / kBinPixels, 0.0, cv::BORDER_REPLICATE);
  return profiles;
}

// One patch [x0, x1) x [y0, y1) of the synthesised white image: each pixel takes the profile of its nearest lens's
// kind of row (`profiles`, on the accumulator's bins, `half` their centre bin) at its offset from that lens
// (NearestLensAt, as LensLabels; lattice coordinates stepped along rows), scaled to the phase's raw levels. Built twice
// (AVX2 and generic) and chosen at run time: with SSE4.1 and later floor and nearbyint are instructions instead of
// library calls; the rounding is RoundHalfAway's (std::lround's, without the call).
__attribute__((target_clones("avx2", "default"))) void SynthesisePatch(const std::array<cv::Mat, kRowKinds>& profiles,
                                                                       const LensletGrid& grid, double half,
                                                                       const std::array<float, 4>& phase_black,
                                                                       const std::array<float, 4>& phase_scale, int x0,
                                                                       int x1, int y0, int y1, RawImage& white) {
  const double c = std::cos(grid.rotation), sn = std::sin(grid.rotation);
  const double along_step = c / grid.spacing_x, across_step = -sn / grid.spacing_y;
  for (int y = y0; y < y1; ++y) {
    std::uint16_t* out = white.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(white.width);
    const double dy = y - grid.origin_y, dx = x0 - grid.origin_x;
    double along = (c * dx + sn * dy) / grid.spacing_x;
    double across = (-sn * dx + c * dy) / grid.spacing_y;
    for (int x = x0; x < x1; ++x, along += along_step, across += across_step) {
      // Offset from the nearest lens centre, in the lattice frame (px), then on the sensor.
      const NearestLens nearest = NearestLensAt(grid, along, across);
      const double offset_along = nearest.offset_along, offset_across = nearest.offset_across;
      const double fx = (c * offset_along - sn * offset_across) / kBinPixels + half;
      const double fy = (sn * offset_along + c * offset_across) / kBinPixels + half;
      const cv::Mat& profile = profiles[static_cast<std::size_t>(grid.Shift(nearest.j))];
      const float value = std::clamp(Bilinear(profile, fx, fy), 0.0f, 1.2f);
      const auto phase = static_cast<std::size_t>(BayerPhase(x, y));
      // RoundHalfAway answers the smallest int beyond +-2e9, where lround's clamp gave 65535 above (levels that
      // hostile metadata can make): those clamp first.
      const float level = std::min(phase_black[phase] + value * phase_scale[phase], 65535.0f);
      out[x] = static_cast<std::uint16_t>(std::clamp(RoundHalfAway(level), 0, 65535));
    }
  }
}

}  // namespace

RawImage EstimateWhiteImageFromCapture(const RawImage& capture, const LytroMetadata& metadata, const LensletGrid& grid,
                                       CaptureWhiteReport* report) {
  const RawFormat& format = metadata.RequireRawFormat();
  if (capture.width != grid.sensor_width || capture.height != grid.sensor_height ||
      capture.pixels.size() != capture.PixelCount())
    throw Error(metadata.source + ": capture and lenslet grid differ in size");
  const PhaseLevels levels = LevelsOf(format, metadata.source);
  const cv::Mat levelled = ApplyLevels(capture, levels);
  // Lytro micro-images are 10-15 px across; the profile's bins grow with the square of the spacing.
  constexpr double kLargestSpacing = 100.0;
  if (!(grid.spacing_x > 0.0 && grid.spacing_x <= kLargestSpacing))
    throw Error(metadata.source + ": a lens spacing of " + std::to_string(grid.spacing_x) +
                " px is beyond what a white image can be estimated for from the capture (at most 100 px)");
  const double reach = kReachFraction * grid.spacing_x, core = kCoreFraction * grid.spacing_x;
  const int bins = 2 * static_cast<int>(std::ceil(reach / kBinPixels)) + 3;
  const long lenses = static_cast<long>(grid.columns) * grid.rows;
  // Tiles of at least ~2000 lenses each (5 x 5 on full Lytro sensors). Real micro-images change shape across the
  // sensor: on the real F01 frame IMG_1 the outer views' brightness relative to the centre view varied across the
  // image by a factor 1.20-1.22 (p95/p5) with one profile, 1.12-1.15 with 5 x 5 tiles of full profiles. (The
  // simulator's profile is the same everywhere: there each tile's correction is noise, and one tile read 13 %
  // BadPix 0.07 on the noisy F01 two-horses capture where 5 x 5 corrected tiles read 20 %.)
  const int tiles = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(lenses) / 2000.0)), 1, 5);

  // 1. Accumulate every usable lens, rows of lenses in parallel, summed in a fixed order (the same white image, to
  // the bit, on every run and thread count). Twice: the second pass normalises each lens by the first pass's profile.
  struct Partial {
    ProfileAccumulator profile;
    long used = 0;
  };
  auto accumulate = [&](const std::vector<cv::Mat>* first_pass) {
    return OrderedParallelSum(
        grid.rows,
        [&] {
          return Partial{ProfileAccumulator(bins, tiles), 0};
        },
        [&](int j, Partial& partial) {
          for (int i = 0; i < grid.columns; ++i) {
            double cx = 0.0, cy = 0.0;
            grid.Centre(i, j, cx, cy);
            const int tx = std::clamp(static_cast<int>(cx / grid.sensor_width * tiles), 0, tiles - 1);
            const int ty = std::clamp(static_cast<int>(cy / grid.sensor_height * tiles), 0, tiles - 1);
            const int tile = ty * tiles + tx, kind = grid.Shift(j);
            const cv::Mat* profile =
                first_pass ? &(*first_pass)[static_cast<std::size_t>(tile * kRowKinds + kind)] : nullptr;
            if (AddLens(levelled, cx, cy, reach, core, tile, kind, profile, partial.profile)) ++partial.used;
          }
        },
        [](Partial& into, const Partial& from) {
          into.profile.Merge(from.profile);
          into.used += from.used;
        });
  };
  const Partial first = accumulate(nullptr);
  const long used = first.used;
  if (used < 50)
    throw Error(metadata.source + ": too few unclipped, lit micro-images (" + std::to_string(used) +
                ") to estimate the white image from the capture");
  const std::vector<cv::Mat> first_profiles = TileProfiles(first.profile);
  const std::vector<cv::Mat> gain_profiles = GainProfiles(first_profiles);
  std::array<cv::Mat, kRowKinds> row_kind_ratios;
  const std::vector<cv::Mat> profiles = TileProfiles(accumulate(&gain_profiles).profile, &row_kind_ratios);

  // 2. Synthesise: each pixel takes the profile at its offset from the nearest lens, blended between tile centres.
  const std::array<double, 4> response = PhaseResponse(metadata, format.mosaic);
  RawImage white;
  white.width = capture.width;
  white.height = capture.height;
  white.pixels.resize(white.PixelCount());
  const double half = 0.5 * (bins - 1);
  // The tile profiles blended once per patch of the sensor (the blend changes over a tile, ~1500 px), then one
  // lookup per pixel (SynthesisePatch).
  constexpr int kPatch = 128;
  const int patches_x = (white.width + kPatch - 1) / kPatch, patches_y = (white.height + kPatch - 1) / kPatch;
  std::array<float, 4> phase_scale{}, phase_black{};
  for (std::size_t phase = 0; phase < 4; ++phase) {
    phase_scale[phase] = static_cast<float>(kWhiteLevel * response[phase] / levels.scale[phase]);
    phase_black[phase] = levels.black[phase];
  }
#pragma omp parallel for schedule(dynamic, 1)
  for (int patch = 0; patch < patches_x * patches_y; ++patch) {
    const int x0 = (patch % patches_x) * kPatch, y0 = (patch / patches_x) * kPatch;
    const int x1 = std::min(white.width, x0 + kPatch), y1 = std::min(white.height, y0 + kPatch);
    // Bilinear weights of the four tile centres around the patch centre.
    auto tile_coordinate = [tiles](double position, int size) {
      return std::clamp((position + 0.5) / size * tiles - 0.5, 0.0, tiles - 1.0);
    };
    const double tx = tile_coordinate(0.5 * (x0 + x1 - 1), white.width);
    const double ty = tile_coordinate(0.5 * (y0 + y1 - 1), white.height);
    const int tx0 = static_cast<int>(tx), ty0 = static_cast<int>(ty);
    const int tx1 = std::min(tx0 + 1, tiles - 1), ty1 = std::min(ty0 + 1, tiles - 1);
    const double ax = tx - tx0, ay = ty - ty0;
    std::array<cv::Mat, kRowKinds> blended;
    for (int kind = 0; kind < kRowKinds; ++kind) {
      auto tile = [&](int t_y, int t_x) -> const cv::Mat& {
        return profiles[static_cast<std::size_t>((t_y * tiles + t_x) * kRowKinds + kind)];
      };
      blended[static_cast<std::size_t>(kind)] = (1 - ay) * (1 - ax) * tile(ty0, tx0) + (1 - ay) * ax * tile(ty0, tx1) +
                                                ay * (1 - ax) * tile(ty1, tx0) + ay * ax * tile(ty1, tx1);
    }
    SynthesisePatch(blended, grid, half, phase_black, phase_scale, x0, x1, y0, y1, white);
  }
  if (report) {
    report->lenses = static_cast<int>(lenses);
    report->lenses_used = static_cast<int>(used);
    report->tiles = tiles;
    // The shifted rows' profile over the unshifted rows' at 0.4 spacings along the row on either side (the sensor's
    // x axis: the lens rows are within a few milliradians of it), averaged.
    const int centre_bin = (bins - 1) / 2, step = static_cast<int>(std::lround(0.4 * grid.spacing_x / kBinPixels));
    double ratio = 0.0;
    for (const int side : {-step, step})
      ratio += 0.5 * row_kind_ratios[1].at<double>(centre_bin, centre_bin + side) /
               row_kind_ratios[0].at<double>(centre_bin, centre_bin + side);
    report->shifted_rows_rim_ratio = ratio;
  }
  return white;
}

}  // namespace lfsp::decode
