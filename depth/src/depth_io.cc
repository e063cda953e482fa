#include "lfsp/depth/depth_io.h"

#include "lfsp/core/image_io.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/visualize.h"

namespace lfsp::depth {

DepthOutputPaths OutputPathsFor(const std::filesystem::path& disparity_pfm) {
  DepthOutputPaths paths;
  paths.disparity = disparity_pfm;
  paths.preview = std::filesystem::path(disparity_pfm).replace_extension(".png");
  std::filesystem::path confidence = disparity_pfm;
  confidence.replace_filename(disparity_pfm.stem().string() + "_confidence.pfm");
  paths.confidence = confidence;
  return paths;
}

void WriteDepthOutputs(const DepthResult& result, const DepthOutputPaths& paths) {
  WritePfm(result.disparity, paths.disparity);
  WritePfm(result.confidence, paths.confidence);
  WriteImage(ColourMapDisparity(result.disparity, result.range), paths.preview, 8);
}

nlohmann::json ToJson(const DepthOptions& options) {
  nlohmann::json json;
  if (options.range) json["range"] = {{"min", options.range->min}, {"max", options.range->max}};
  json["labels"] = options.labels;
  json["occlusion_handling"] = options.occlusion_handling;
  json["regularise"] = options.regularise;
  json["cost"] = {{"detail_sigma", options.cost.detail_sigma},
                  {"detail_truncation", options.cost.detail_truncation},
                  {"detail_normalise_sigma", options.cost.detail_normalise_sigma},
                  {"detail_normalise_epsilon", options.cost.detail_normalise_epsilon},
                  {"colour_weight", options.cost.colour_weight},
                  {"colour_deadzone", options.cost.colour_deadzone},
                  {"colour_truncation", options.cost.colour_truncation},
                  {"half_patch_penalty", options.cost.half_patch_penalty},
                  {"halves_agree_labels", options.cost.halves_agree_labels},
                  {"along_edge_penalty", options.cost.along_edge_penalty},
                  {"sampler", SamplerName(options.cost.sampler)}};
  json["occlusion"] = {{"canny_low", options.occlusion.canny_low},
                       {"canny_high", options.occlusion.canny_high},
                       {"blur_sigma", options.occlusion.blur_sigma},
                       {"along_window_sigma", options.occlusion.along_window_sigma},
                       {"along_min_coherence", options.occlusion.along_min_coherence},
                       {"radius", options.occlusion.radius}};
  json["thin_structures"] = {{"reach", options.thin_structures.reach},
                             {"margin", options.thin_structures.margin},
                             {"colour_difference", options.thin_structures.colour_difference},
                             {"blend_difference", options.thin_structures.blend_difference}};
  json["occluder_horizon"] = {{"slack", options.occluder_horizon.slack},
                              {"widening", options.occluder_horizon.widening}};
  json["sgm"] = {{"p1", options.sgm.p1}, {"p2", options.sgm.p2}, {"edge_sigma", options.sgm.edge_sigma}};
  json["sub_label"] = {{"radius", options.sub_label.radius},
                       {"sigma", options.sub_label.sigma},
                       {"saturation", options.sub_label.saturation}};
  json["plane_fit"] = {{"enabled", options.plane_fit},
                       {"region_size", options.plane.region_size},
                       {"support_threshold", options.plane.support_threshold},
                       {"inlier_distance", options.plane.inlier_distance},
                       {"min_inlier_fraction", options.plane.min_inlier_fraction},
                       {"min_support", options.plane.min_support}};
  json["median"] = {{"radius", options.median.radius},
                    {"sigma", options.median.sigma},
                    {"wide_radius", options.median.wide_radius},
                    {"wide_threshold", options.median.wide_threshold}};
  json["textureless_fill"] = {{"smoothness", options.textureless_fill.smoothness},
                              {"texture_scale", options.textureless_fill.texture_scale},
                              {"jump", options.textureless_fill.jump}};
  json["mixed_edges"] = {{"max_share", options.mixed_edges.max_share},
                         {"jump", options.mixed_edges.jump},
                         {"depth", options.mixed_edges.depth},
                         {"rgb_separation", options.mixed_edges.rgb_separation},
                         {"chroma_separation", options.mixed_edges.chroma_separation},
                         {"rounds", options.mixed_edges.rounds}};
  json["presmooth_sigma"] = options.presmooth_sigma;
  json["excluded_ring"] = options.cost.excluded_ring;
  json["detail_weight"] = options.cost.detail_weight;
  return json;
}

nlohmann::ordered_json AutomaticChoicesToJson(const DepthResult& result) {
  return {
      {"noise_sigma", result.noise_sigma},           {"noise_sigma_lower_quartile", result.noise_sigma_lower_quartile},
      {"fine_band_snr", result.fine_band_snr},       {"presmooth_sigma", result.presmooth_sigma},
      {"occlusion_radius", result.occlusion_radius}, {"sampler", SamplerName(result.sampler)},
      {"excluded_ring", result.excluded_ring},       {"detail_weight", result.detail_weight},
      {"channel_weights", result.channel_weights},   {"sgm_penalties", {{"p1", result.sgm.p1}, {"p2", result.sgm.p2}}}};
}

}  // namespace lfsp::depth
