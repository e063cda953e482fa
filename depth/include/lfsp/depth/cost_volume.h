#pragma once

#include <array>

#include <cstddef>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/depth/occlusion.h"

namespace lfsp::depth {

// A matching cost per centre-view pixel and disparity label, stored [y][x][label] so each pixel's cost curve is
// contiguous (what semi-global aggregation and the refinement read). Lower is better.
class CostVolume {
 public:
  CostVolume() = default;
  CostVolume(int width, int height, int labels, float fill = 0.0f)
      : width_(width), height_(height), labels_(labels), data_(Size(width, height, labels), fill) {}

  int width() const { return width_; }
  int height() const { return height_; }
  int labels() const { return labels_; }
  float* Curve(int y, int x) { return data_.data() + Offset(y, x); }
  const float* Curve(int y, int x) const { return data_.data() + Offset(y, x); }
  float* data() { return data_.data(); }
  const float* data() const { return data_.data(); }

 private:
  static std::size_t Size(int w, int h, int l) {
    return static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(l);
  }
  std::size_t Offset(int y, int x) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) *
           static_cast<std::size_t>(labels_);
  }
  int width_ = 0;
  int height_ = 0;
  int labels_ = 0;
  std::vector<float> data_;
};

// The disparity of each label: `count` values evenly spaced from min to max inclusive.
std::vector<float> LabelDisparities(float min, float max, int count);

// How a view is resampled at the sub-pixel shift a label predicts (noise_matched_kernel.h).
enum class Sampler {
  kAutomatic,     // EstimateDepth: noise-matched on noisy views and lenslet decodes, else bilinear
  kBilinear,      // sharpest; on noisy views its noise varies with the shift and biases the cost
  kNoiseMatched,  // cubic, the same noise at every shift; blurs by the cubic B-spline (the centre view too)
  kCubic,         // Keys' cubic convolution (a = -1/2): sharp, and its blur's second moment is 0 at every shift
};

// "automatic", "bilinear", "noise-matched", "cubic"; SamplerFromString throws lfsp::Error on any other name.
std::string SamplerName(Sampler sampler);
Sampler SamplerFromString(const std::string& name);

// Each non-centre view contributes, per pixel and label, a truncated L1 difference to the centre view in two
// representations of the images:
//  - detail: the high-pass grey image G - Gaussian(G, detail_sigma), G the mean of RGB, divided by its local RMS
//    (contrast normalisation). It keeps the faint texture of weakly textured, dim surfaces at full weight but drops
//    slow shading and small brightness differences between views, which otherwise bias the minimum of the plain
//    colour cost on shadowed surfaces (measured on HCI antinous: BadPix 0.07 18% -> 6%);
//  - colour: the views themselves, weighted lower. High-pass images lose the contrast between an occluder's
//    interior and its background, so without this term backgrounds next to objects take the objects' depth.
struct CostOptions {
  float detail_sigma = 1.0f;                // pixels; 0 = no detail term
  float detail_truncation = 0.5f;           // cap of the per-view |normalised grey detail| difference
  float detail_normalise_sigma = 4.0f;      // > 0: divide detail by its local RMS (Gaussian window), 0 = off
  float detail_normalise_epsilon = 0.005f;  // added to the RMS, so flat noise is not blown up
  // Weight of the detail term; < 0 = automatic (EstimateDepth: DetailWeightFor, from the detail band's signal and
  // noise; BuildCostVolume alone reads < 0 as 1).
  float detail_weight = -1.0f;
  float colour_weight = 3.0f;  // 0 = no colour term
  // Weights of |dR|, |dG|, |dB| in the colour term (their sum 3 keeps the term's scale); a negative first weight =
  // automatic (EstimateDepth: ChannelWeightsForNoise). BuildCostVolume alone reads a negative one as 1, 1, 1.
  std::array<float, 3> channel_weights = {-1.0f, -1.0f, -1.0f};
  float colour_deadzone = 0.0f;     // colour differences below this are free (shading, view-dependent brightness)
  float colour_truncation = 0.12f;  // cap of the per-view sum of |RGB| differences, so occluded views cannot dominate
  // Near an edge, a half of the angular patch replaces the whole one only where its cost times this factor is
  // still lower: half the views are noisier, so on textured, unoccluded surfaces the whole patch must win.
  float half_patch_penalty = 1.0f;
  // Near an edge, which half of the angular patch may stand in for the whole one. -1 (default): the lower envelope
  // of the two halves, label by label. N >= 0: the two halves' best labels within N labels of each other mean that
  // no occluder hides the pixel from either half, and the whole patch stays; otherwise only the half whose best label
  // costs less stands in. On clean renderings N = 3 reads thin bars right where the envelope read them too near
  // (the bars scene's 4 px bar at 0.40 px: 0.45-0.47; BadPix 0.07 1.54 -> 1.05 %; since the occluder horizon keeps the
  // envelope's dips off that bar, 1.35 by default against 1.02 % with N = 3), but on the simulated cameras' decodes,
  // whose views are blurred by the optics, it spreads the foreground instead (F01 two-horses capture 2.86 -> 5.43 %,
  // 99.8 % of the new bad pixels nearer): BENCHMARKS.md, thirtieth session.
  int halves_agree_labels = -1;
  // Near an edge, the views along it (the pair of opposite sectors nearest its direction, OcclusionMap::along)
  // replace the whole patch where their cost times this factor is lower; 0 = off. A pixel in a gap between two
  // occluders parallel to the edge is hidden on both sides of the split, but these views see it. They are few and
  // cannot see the edge's own shift (their shifts run along it), so they must win clearly. Measured (BadPix 0.07 % /
  // MSE x100): off: comb 10.5 / 31.8, occluders 5.1 / 2.7; 2.5: comb 3.0 / 7.3, occluders 3.8 / 3.3; 2.0 is a little
  // better on comb but 1.5 puts occluders at 23 %, so 2.5 keeps a margin.
  float along_edge_penalty = 2.5f;
  // Views within this many steps of the centre view (Chebyshev distance) are left out of the cost; < 0 =
  // automatic (EstimateDepth: ExcludedRingFor, 2 or 1 on light fields decoded from a lenslet sensor, else 0). In a
  // lenslet decode,
  // neighbouring views are neighbouring sensor pixels of one micro-image, and demosaicking and the sub-pixel
  // lookup mix them: the centre view shares noise with its neighbours at zero shift, which draws every disparity
  // towards 0 (full-size F01 strips with sensor noise read 0.72x their disparity).
  int excluded_ring = -1;
  Sampler sampler = Sampler::kAutomatic;  // BuildCostVolume alone reads automatic as bilinear
  // Gaussian smoothing of every view before matching, pixels (PresmoothView); 0 = none. EstimateDepth sets it from
  // DepthOptions::presmooth_sigma after its automatic choice.
  double presmooth_sigma = 0.0;
  int tile_rows = 4;  // rows per work item: each view's rows of one tile stay in cache across all labels
};

// The largest cost one view can add (both terms at their truncation): colour_weight x colour_truncation, plus
// detail_weight x detail_truncation when there is a detail term (an automatic detail weight counts as 1, as in
// BuildCostVolume). The default options give 0.86.
float CostRange(const CostOptions& options);

// The costs of the partial angular patches a pixel near an edge may use instead of the whole one (penalties of
// CostOptions applied): the cheaper half of the edge's split, and the views along the edge. Infinite where a pixel
// may not use them: not an occlusion candidate, or a half of its split without views (and `along` wherever the
// views along the edge are off or there are none).
struct OcclusionAlternatives {
  CostVolume half;
  CostVolume along;
};

// Photo-consistency cost of every centre-view pixel at every label, computed view by view and tile by tile from
// one copy of the views' features, planar by rows (RGB, and the detail image when the detail term has weight; the
// centre view's blurred too for the noise-matched sampler): each non-centre view is resampled at the sub-pixel shift
// the label predicts (CostOptions::sampler) and compared with the centre view (see CostOptions). Views are accumulated
// per angular sector, so a pixel flagged by `occlusion` can use only the half of the angular patch on one side of its
// edge (the cheaper half: Wang et al.'s split, chosen from the centre view's edge orientation), or the views along the
// edge. Without `alternatives` (nullptr) the cheapest of the whole patch and these is returned; with it, the returned
// volume is the whole patch's cost and the partial patches' costs go to `alternatives` (EstimateDepth admits them pixel
// by pixel: occlusion_alternatives.h). Without `occlusion` (nullptr) every pixel averages all views. The light field
// must be RGB (3 channels).
CostVolume BuildCostVolume(const LightField& light_field, const std::vector<float>& disparities,
                           const CostOptions& options, const OcclusionMap* occlusion,
                           OcclusionAlternatives* alternatives = nullptr);

// Filters every label slice of the volume with a guided filter (He et al.) steered by the centre view: window
// (2 radius + 1)^2, regularisation epsilon. Costs are averaged over similar-coloured neighbours only, which lifts
// the faint texture of weakly textured surfaces above the noise without blurring depth across colour edges.
void AggregateLocally(CostVolume& cost, const cv::Mat& guide_rgb, int radius, float epsilon);

}  // namespace lfsp::depth
