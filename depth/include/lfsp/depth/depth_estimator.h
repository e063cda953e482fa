#pragma once

#include <array>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lfsp/core/light_field.h"
#include "lfsp/core/metadata.h"
#include "lfsp/depth/cost_volume.h"
#include "lfsp/depth/mixed_edge_pixels.h"
#include "lfsp/depth/occlusion.h"
#include "lfsp/depth/occlusion_alternatives.h"
#include "lfsp/depth/plane_fit.h"
#include "lfsp/depth/refinement.h"
#include "lfsp/depth/sgm.h"
#include "lfsp/depth/textureless_fill.h"

namespace lfsp::depth {

// Every parameter of the method. The defaults are the one parameter set used for all scenes.
struct DepthOptions {
  std::optional<DisparityRange> range;  // default: the light field's metadata (HCI parameters.cfg disp_min/max)
  int labels = 80;
  bool occlusion_handling = true;
  bool regularise = true;  // semi-global aggregation; false = plain winner-take-all on the cost volume
  CostOptions cost;
  OcclusionOptions occlusion;
  // Near edges, where a partial angular patch may replace the whole one: refused on thin structures in front.
  ThinStructureOptions thin_structures;
  // ... and only at the labels where a nearer surface around can hide the pixel from some view.
  OccluderHorizonOptions occluder_horizon;
  int aggregation_radius = 0;         // edge-aware (guided filter) cost aggregation before SGM (0 = off)
  float aggregation_epsilon = 1e-3f;  // guided filter regularisation (squared intensity units)
  SgmOptions sgm;
  SubLabelOptions sub_label;  // the sub-label offsets of the semi-global labels, from the data cost (refinement.h)
  bool plane_fit = false;     // slanted-plane refinement of textureless pixels (see plane_fit.h)
  PlaneFitOptions plane;
  // Gaussian smoothing of every view before matching, pixels: < 0 = automatic (AutomaticPresmoothSigma: 0.6 px on
  // noisy views, none on clean ones), 0 = off.
  float presmooth_sigma = -1.0f;
  MedianOptions median;  // the weighted-median refinement (refinement.h)
  // After the median: textureless pixels interpolated from the textured ones around them (textureless_fill.h).
  TexturelessFillOptions textureless_fill;
  // Last: the pixels along occlusion edges whose colour is mostly the farther surface's go to it
  // (mixed_edge_pixels.h).
  MixedEdgeOptions mixed_edges;
};

struct DepthResult {
  DisparityMap disparity;   // centre view, px per view step, HCI convention
  DisparityMap confidence;  // [0, 1]
  DisparityRange range;
  std::string range_source;         // "options", "metadata" or "estimated from the views"
  int occlusion_candidates = 0;     // pixels that used the edge-split angular patch
  int thin_structure_refusals = 0;  // (pixel, partial patch) pairs refused on thin structures in front
  int mixed_edge_moves = 0;  // moves to a farther side (ReassignMixedEdgePixels; a pixel moved along two counts twice)
  double occlusion_radius = 0.0;            // the radius used (after the automatic choice)
  double noise_sigma = 0.0;                 // estimated noise of the centre view (Immerkaer), sample units
  double noise_sigma_lower_quartile = 0.0;  // the same from the lower quartile (what the presmoothing follows)
  double fine_band_snr = 0.0;               // FineBandSignalToNoise of the unsmoothed centre view
  double presmooth_sigma = 0.0;             // the smoothing used, pixels (after the automatic choice)
  Sampler sampler = Sampler::kBilinear;     // the cost's resampling (after the automatic choice)
  int excluded_ring = 0;       // views this close to the centre left out of the cost (after the automatic choice)
  float detail_weight = 1.0f;  // weight of the cost's detail term (after the automatic choice)
  std::array<float, 3> channel_weights{1.0f, 1.0f, 1.0f};  // of |dR|, |dG|, |dB| (after the automatic choice)
  SgmOptions sgm;          // the semi-global penalties used (PenaltiesForCost: scaled to the cost's range)
  nlohmann::json timings;  // seconds per step
};

// The disparity range to use: the options' if given, else the metadata's, else estimated from the views
// (EstimateDisparityRange, logged). `source`, when given, says which.
DisparityRange ResolveDisparityRange(const LightField& light_field, const DepthOptions& options,
                                     std::string* source = nullptr);

// Occlusion-aware centre-view disparity: cost volume (with the half-patch choice near edges), semi-global
// aggregation, sub-label refinement, weighted median, textureless fill, mixed edge pixels. Throws lfsp::Error on
// unusable input.
DepthResult EstimateDepth(const LightField& light_field, const DepthOptions& options);

}  // namespace lfsp::depth
