#include "lfsp/depth/depth_estimator.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>

#include "lfsp/core/error.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/stopwatch.h"
#include "lfsp/depth/detail_weight.h"
#include "lfsp/depth/disparity_range.h"
#include "lfsp/depth/occlusion_alternatives.h"
#include "lfsp/depth/presmooth.h"

namespace lfsp::depth {
namespace {

// Whether the partial angular patches are admitted pixel by pixel (occlusion_alternatives.h) rather than everywhere.
bool AdmitsPartialPatches(const DepthOptions& options) {
  return options.occlusion_handling && (options.thin_structures.reach > 0 || options.occluder_horizon.slack >= 0.0f);
}

// How many steps EstimateDepth times (as many laps as it makes).
std::size_t StepsOf(const DepthOptions& options) {
  return 4 + (AdmitsPartialPatches(options) ? 1 : 0) + (options.aggregation_radius > 0 ? 1 : 0) +
         (options.regularise ? 2 : 0) + (options.regularise && options.plane_fit ? 1 : 0) +
         (options.regularise && options.textureless_fill.smoothness > 0.0f ? 1 : 0) +
         (options.regularise && options.mixed_edges.max_share > 0.0f ? 1 : 0);
}

}  // namespace

DisparityRange ResolveDisparityRange(const LightField& light_field, const DepthOptions& options, std::string* source) {
  std::optional<DisparityRange> range = options.range;
  std::string from = "options";
  if (!range) {
    range = DisparityRangeFromMetadata(light_field.metadata);
    from = "metadata";
  }
  if (!range) {
    const RangeEstimate estimate = EstimateDisparityRange(light_field);
    range = estimate.range;
    from = "estimated from the views";
    spdlog::info(
        "disparity range {:.2f} .. {:.2f} px per view step estimated from the views (coarse sweep over "
        "+-{:.1f}: {} pixels measured {:.2f} .. {:.2f}); {}/{} override it",
        range->min, range->max, estimate.searched, estimate.pixels_used, estimate.measured.min, estimate.measured.max,
        OptionName("dmin"), OptionName("dmax"));
  }
  if (!std::isfinite(range->min) || !std::isfinite(range->max) || !(range->max > range->min)) {
    throw Error("depth: invalid disparity range [" + std::to_string(range->min) + ", " + std::to_string(range->max) +
                "]");
  }
  if (source) *source = from;
  return *range;
}

DepthResult EstimateDepth(const LightField& light_field, const DepthOptions& options) {
  DepthResult result;
  result.range = ResolveDisparityRange(light_field, options, &result.range_source);
  const std::vector<float> disparities = LabelDisparities(result.range.min, result.range.max, options.labels);
  if (light_field.shape().channels != 3) {
    throw Error("depth: the light field must hold RGB views (got " + ToString(light_field.shape()) + ")");
  }
  // Each step's seconds into the timings, and one tick of the progress display (drawn only on a terminal).
  Stopwatch stopwatch;
  Progress progress("depth", StepsOf(options));
  const auto lap = [&](const char* step) {
    result.timings[step] = stopwatch.Lap();
    progress.Tick();
  };
  // Noisy views (lenslet decodes, low light) are smoothed a little and resampled by the noise-matched kernel. The
  // smoothing follows the lower-quartile estimate, which a clean view's fine sharp texture does not raise; the
  // sampler follows the median's, which it does, and such texture needs the noise-matched kernel too (presmooth.h).
  const cv::Mat raw_centre = light_field.View(light_field.shape().Centre());
  const std::vector<double> channel_noise = EstimateNoiseSigmaPerChannel(raw_centre);
  result.noise_sigma = *std::max_element(channel_noise.begin(), channel_noise.end());  // EstimateChannelNoiseSigma
  result.noise_sigma_lower_quartile = EstimateChannelNoiseSigmaLowerQuartile(raw_centre);
  result.fine_band_snr = FineBandSignalToNoise(raw_centre, options.cost);
  result.presmooth_sigma = options.presmooth_sigma < 0.0f
                               ? AutomaticPresmoothSigma(light_field, result.noise_sigma_lower_quartile)
                               : options.presmooth_sigma;
  // The views are presmoothed as the cost volume's features are made; the steps that read the centre view read it
  // smoothed alike.
  cv::Mat centre;  // not a header of raw_centre: the smoothing would write into the light field
  if (result.presmooth_sigma > 0.0)
    PresmoothView(raw_centre, result.presmooth_sigma, centre);
  else
    centre = raw_centre;
  lap("presmooth");

  std::optional<OcclusionMap> occlusion;
  if (options.occlusion_handling) {
    OcclusionOptions occlusion_options = options.occlusion;
    if (occlusion_options.radius <= 0.0) {
      occlusion_options.radius = AutomaticOcclusionRadius(light_field.shape().nu, light_field.shape().nv,
                                                          result.range.min, result.range.max, result.presmooth_sigma);
    }
    result.occlusion_radius = occlusion_options.radius;
    occlusion = DetectOcclusionEdges(centre, occlusion_options);
    result.occlusion_candidates = occlusion->Candidates();
  }
  lap("occlusion_edges");
  CostOptions cost_options = options.cost;
  cost_options.presmooth_sigma = result.presmooth_sigma;
  if (cost_options.excluded_ring < 0) cost_options.excluded_ring = ExcludedRingFor(light_field);
  result.excluded_ring = cost_options.excluded_ring;
  if (cost_options.sampler == Sampler::kAutomatic)
    cost_options.sampler = AutomaticSampler(light_field, result.noise_sigma);
  result.sampler = cost_options.sampler;
  if (cost_options.detail_weight < 0.0f)
    cost_options.detail_weight = DetailWeightFor(raw_centre, centre, result.presmooth_sigma,
                                                 DecodedFromSensor(light_field), result.fine_band_snr, cost_options);
  result.detail_weight = cost_options.detail_weight;
  if (cost_options.channel_weights[0] < 0.0f) cost_options.channel_weights = ChannelWeightsForNoise(channel_noise);
  result.channel_weights = cost_options.channel_weights;
  result.sgm = PenaltiesForCost(options.sgm, cost_options);
  OcclusionAlternatives alternatives;
  const bool admit_partial_patches = occlusion && AdmitsPartialPatches(options);
  CostVolume cost = BuildCostVolume(light_field, disparities, cost_options, occlusion ? &*occlusion : nullptr,
                                    admit_partial_patches ? &alternatives : nullptr);
  lap("cost_volume");
  if (admit_partial_patches) {
    // The whole patch's disparity, through the same semi-global pass as the final one (without local aggregation
    // or refinement): it keeps thin structures and every other occluder in front (occlusion_alternatives.h).
    const DisparityMap whole_patch =
        options.regularise ? SelectDisparity(AggregateSemiGlobal(cost, centre, result.sgm), disparities).disparity
                           : SelectDisparity(cost, disparities).disparity;
    const LightFieldShape& shape = light_field.shape();
    result.thin_structure_refusals = AdmitOcclusionAlternatives(
        cost, alternatives, whole_patch, disparities, *occlusion, centre, options.thin_structures,
        options.occluder_horizon, LongestViewOffset(shape.nu, shape.nv));
    alternatives = OcclusionAlternatives();
    lap("occlusion_alternatives");
  }
  if (options.aggregation_radius > 0) {
    AggregateLocally(cost, centre, options.aggregation_radius, options.aggregation_epsilon);
    lap("local_aggregation");
  }
  CostVolume raw_cost;  // the data cost, kept for the sub-label offsets and the plane fit's data support
  if (options.regularise) {
    CostVolume aggregated = AggregateSemiGlobal(cost, centre, result.sgm);
    if (options.plane_fit || options.sub_label.radius > 0) raw_cost = std::move(cost);
    cost = std::move(aggregated);
    lap("semi_global");
  }
  DisparityEstimate estimate = SelectDisparity(cost, disparities);
  if (options.regularise) {
    SubLabelOptions sub_label = options.sub_label;
    sub_label.p1 = result.sgm.p1;
    RefineSubLabelFromData(estimate.disparity, cost, raw_cost, disparities, centre, sub_label);
  }
  lap("select");
  if (options.regularise && options.plane_fit) {
    const DisparityMap support = DataSupport(raw_cost, estimate.disparity, disparities);
    raw_cost = CostVolume();
    PlaneFitRefine(estimate.disparity, support, centre, options.plane);
    lap("plane_fit");
  }
  if (options.regularise) {
    WeightedMedianRefine(estimate.disparity, centre, options.median);
    lap("weighted_median");
    if (options.textureless_fill.smoothness > 0.0f) {
      FillTexturelessDisparity(estimate.disparity, centre, options.textureless_fill);
      lap("textureless_fill");
    }
    if (options.mixed_edges.max_share > 0.0f) {
      // The unsmoothed centre: a mixed pixel's colour is what it is before the presmoothing mixes it further.
      result.mixed_edge_moves = ReassignMixedEdgePixels(estimate.disparity, raw_centre, options.mixed_edges);
      lap("mixed_edges");
    }
  }
  LowerConfidenceNearDepthEdges(estimate.confidence, estimate.disparity);
  if (options.regularise) RemoveConfidenceStreaks(estimate.confidence);
  result.disparity = std::move(estimate.disparity);
  result.confidence = std::move(estimate.confidence);
  return result;
}

}  // namespace lfsp::depth
