#include "metric_descriptions.h"

#include <array>

namespace lfsp::report {
namespace {

constexpr std::string_view kHci = "Honauer et al., ACCV 2016 (HCI 4D light-field benchmark)";
constexpr std::string_view kLfsp = "Zhu, Zhang, Wang, TIP 2020 (LFSP)";
constexpr std::string_view kKhan = "Khan et al., ICCV 2019";
constexpr std::string_view kNeubert = "Neubert, Protzel 2012 (corrected UE), as Khan et al., ICCV 2019 report it";

// The one table of metric descriptions. Keys follow the metrics JSON: depth.<region>.*, segmentation.*,
// segmentation.khan.*, decode_vs_truth.* (apps/stages/evaluate_stage.cc, apps/pipeline/truth_comparison.cc).
constexpr std::array kDescriptions = {
    // Depth against the true disparity (depth/include/lfsp/depth/metrics.h).
    MetricDescription{"depth.*.mse_x100", "Mean squared disparity error x100", "px^2 x 100", Better::kLower,
                      "100 x mean of (estimate - truth)^2 over the view less a 15 px frame", kHci},
    MetricDescription{"depth.*.badpix_0.07", "Bad pixels at 0.07 px", "%", Better::kLower,
                      "share of pixels whose disparity is off by more than 0.07 px", kHci},
    MetricDescription{"depth.*.badpix_0.03", "Bad pixels at 0.03 px", "%", Better::kLower,
                      "share of pixels whose disparity is off by more than 0.03 px", kHci},
    MetricDescription{"depth.*.badpix_0.01", "Bad pixels at 0.01 px", "%", Better::kLower,
                      "share of pixels whose disparity is off by more than 0.01 px", kHci},
    MetricDescription{"depth.*.q25", "Quartile error", "1/100 px", Better::kLower,
                      "the 25th percentile of |estimate - truth| x 100: how exact the better quarter is", kHci},
    MetricDescription{"depth.*.pixels", "Pixels scored", "pixels", Better::kNeither,
                      "the pixels the figures above are taken over", ""},
    MetricDescription{"depth.definition.boundary_px", "Frame left out", "px", Better::kNeither,
                      "pixels at each side of the view that the depth figures leave out", kHci},
    MetricDescription{"depth.definition.discontinuity_jump_px", "Depth-edge step", "px/view", Better::kNeither,
                      "a step of the true disparity between neighbours this large is a depth edge", ""},
    MetricDescription{"depth.definition.discontinuity_radius_px", "Depth-edge band", "px", Better::kNeither,
                      "pixels this close to a depth edge count as near depth edges", ""},
    MetricDescription{"depth.definition.masks.*", "Region from", "", Better::kNeither,
                      "the scene's mask file, or derived from the true disparity", kHci},
    // The benchmark's region figures (depth/include/lfsp/depth/region_metrics.h).
    MetricDescription{"depth.fattening_index.*", "Fattening index", "%", Better::kLower,
                      "of the bad pixels (off by 0.07 px), the share that read nearer than the truth: the "
                      "foreground spread over the background (50: no bias)",
                      kHci},
    MetricDescription{"depth.bumpiness.planes", "Bumpiness on planes", "px/px^2 x 100", Better::kLower,
                      "mean Frobenius norm of the error's Hessian on planar surfaces, clipped at 0.05", kHci},
    MetricDescription{"depth.bumpiness.smooth_surfaces", "Bumpiness on smooth surfaces", "px/px^2 x 100",
                      Better::kLower, "the same on smooth curved surfaces", kHci},
    MetricDescription{"depth.bumpiness.plane_pixels", "Plane pixels", "pixels", Better::kNeither,
                      "pixels on planar surfaces, where the bumpiness on planes is taken", kHci},
    MetricDescription{"depth.bumpiness.smooth_surface_pixels", "Smooth-surface pixels", "pixels", Better::kNeither,
                      "pixels on smooth curved surfaces", kHci},
    MetricDescription{"depth.sparsification.area_mse_x100", "Sparsification area", "px^2 x 100", Better::kLower,
                      "mean MSE of the most confident 1 ... 100 % of the pixels: how well the confidence ranks errors",
                      "Ilg et al., ECCV 2018"},
    MetricDescription{"depth.sparsification.oracle_area_mse_x100", "Sparsification area of the oracle", "px^2 x 100",
                      Better::kNeither, "the same with the pixels ordered by their true error: the floor",
                      "Ilg et al., ECCV 2018"},
    MetricDescription{"depth.sparsification.area_between", "Area above the oracle (AUSE)", "px^2 x 100", Better::kLower,
                      "sparsification area minus the oracle's; 0: errors ranked perfectly", "Ilg et al., ECCV 2018"},
    MetricDescription{"depth.sparsification.*", "Sparsification curve", "px^2 x 100", Better::kNeither,
                      "the MSE of the most confident 1 ... 100 % of the pixels, per percent", "Ilg et al., ECCV 2018"},
    // Superpixels (segment/include/lfsp/segment/metrics.h, khan_metrics.h).
    MetricDescription{"segmentation.labels", "Superpixels", "", Better::kNeither,
                      "distinct labels in the whole light field", ""},
    MetricDescription{"segmentation.centre_labels", "Superpixels in the centre view", "", Better::kNeither,
                      "distinct labels in the centre view", ""},
    MetricDescription{"segmentation.elr", "Effective label ratio", "", Better::kHigher,
                      "labels in the centre view / labels anywhere; 1: no label lives only in side views", kLfsp},
    MetricDescription{"segmentation.compactness", "Compactness", "", Better::kHigher,
                      "area-weighted 4 pi area / perimeter^2 of the superpixels; 1 would be discs",
                      "Schick et al., ICPR 2012"},
    MetricDescription{"segmentation.boundary_recall", "Boundary recall", "", Better::kHigher,
                      "share of true object edges with a superpixel edge within 2 px, mean over views", kLfsp},
    MetricDescription{"segmentation.undersegmentation_error", "Under-segmentation error", "", Better::kLower,
                      "share of pixels of superpixels that leak across a true object edge, mean over views", kNeubert},
    MetricDescription{"segmentation.undersegmentation_error_region", "Under-segmentation error, per object", "",
                      Better::kLower, "the leak measured per true object, then averaged over objects", kKhan},
    MetricDescription{"segmentation.achievable_segmentation_accuracy", "Achievable segmentation accuracy", "",
                      Better::kHigher, "share of pixels right if every superpixel took its best object", kLfsp},
    MetricDescription{"segmentation.self_similarity", "Self-similarity", "px", Better::kLower,
                      "how far a superpixel's centroid in the side views lands from its centre-view centroid once "
                      "carried by the true disparity",
                      kLfsp},
    MetricDescription{"segmentation.self_similarity_in_frame", "Self-similarity, in frame", "px", Better::kLower,
                      "the same, leaving out rays that land outside the centre view", kLfsp},
    MetricDescription{
        "segmentation.self_similarity_reference", "Self-similarity of a perfect carry", "px", Better::kNeither,
        "what the centre labels carried to every view by the truth score: the floor occlusions set", kLfsp},
    MetricDescription{"segmentation.self_similarity_reference_in_frame", "Self-similarity of a perfect carry, in frame",
                      "px", Better::kNeither, "the same, in frame", kLfsp},
    MetricDescription{"segmentation.labels_per_pixel", "Labels per pixel", "", Better::kLower,
                      "labels a scene point gets across the views that see it; 1: perfectly view-consistent", kKhan},
    MetricDescription{"segmentation.khan.size", "Superpixel size", "px", Better::kNeither,
                      "mean square root of the centre-view superpixels' areas", kKhan},
    MetricDescription{"segmentation.khan.self_similarity", "Self-similarity (Khan)", "px", Better::kLower,
                      "centroid distance to the centre view, averaged over every label and view", kKhan},
    MetricDescription{"segmentation.khan.labels_per_pixel", "Labels per pixel (Khan)", "", Better::kLower,
                      "labels carried onto a centre pixel from all views, disocclusions included; 1 is best", kKhan},
    MetricDescription{"segmentation.khan.boundary_recall", "Boundary recall (Khan)", "", Better::kHigher,
                      "share of true edge pixels (Sobel band) with a superpixel edge within 2 px", kKhan},
    MetricDescription{"segmentation.khan.undersegmentation_error", "Under-segmentation error (Khan)", "",
                      Better::kLower, "leak across true objects, per object then averaged", kKhan},
    MetricDescription{"segmentation.khan.achievable_accuracy", "Achievable accuracy (Khan)", "", Better::kHigher,
                      "share of rays right if each superpixel took one object for the whole light field", kKhan},
    MetricDescription{"segmentation.khan.self_similarity_reference", "Self-similarity of a perfect carry (Khan)", "px",
                      Better::kNeither, "what a perfectly consistent segmentation scores", kKhan},
    MetricDescription{"segmentation.khan.labels_per_pixel_reference", "Labels per pixel of a perfect carry (Khan)", "",
                      Better::kNeither, "what a perfectly consistent segmentation scores", kKhan},
    // The depth maps themselves, no ground truth needed (depth/include/lfsp/depth/lattice_peak.h).
    MetricDescription{"depth_maps.lattice_peak.*.ratio", "Lens lattice in the map", "", Better::kLower,
                      "the strongest spectral peak at a frequency where the lens lattice of a lenslet decode shows "
                      "in the views, over the spectrum's median around it (Welch, 64 px blocks): about 1 is none, "
                      "a visible lattice reads several",
                      ""},
    MetricDescription{"depth_maps.lattice_peak.*.fx", "Its frequency across", "cycles/px", Better::kNeither,
                      "horizontal frequency of that peak", ""},
    MetricDescription{"depth_maps.lattice_peak.*.fy", "Its frequency down", "cycles/px", Better::kNeither,
                      "vertical frequency of that peak", ""},
    // The decode of a simulated capture against its ideal light field (apps/pipeline/truth_comparison.h).
    MetricDescription{"decode_vs_truth.centre_view.mean_abs_error_rms", "Centre-view error (RMS)", "linear light",
                      Better::kLower, "RMS of the decoded centre view's error against the ideal one, gains matched",
                      ""},
    MetricDescription{"decode_vs_truth.centre_view.psnr_db", "Centre-view PSNR", "dB", Better::kHigher,
                      "peak signal-to-noise ratio of the decoded centre view against the ideal one", ""},
    MetricDescription{"decode_vs_truth.registration.min_weight", "Weight needed to register", "", Better::kNeither,
                      "views dimmer than this mean weight (vignetting) are not registered", ""},
    MetricDescription{"decode_vs_truth.registration.depth_edge_margin_px", "Depth-edge margin", "px", Better::kNeither,
                      "pixels this close to a true depth edge are left out of the registration", ""},
    MetricDescription{"decode_vs_truth.registration.views_registered", "Views registered", "views", Better::kHigher,
                      "views bright enough to register on the ideal light field", ""},
    MetricDescription{"decode_vs_truth.registration.worst_shift_px", "Worst view shift", "px", Better::kLower,
                      "the largest shift that registers a decoded view on its ideal view: 0 is a perfect grid", ""},
    MetricDescription{"decode_vs_truth.registration.views", "Per-view registration shift", "px", Better::kLower,
                      "the shift (dx, dy) that registers each decoded view on its ideal view, in linear light; a "
                      "pattern across the views points at the lenslet grid or the resampling",
                      ""},
};

bool Matches(std::string_view pattern, std::string_view key) {
  while (true) {
    const std::size_t p = pattern.find('.');
    const std::size_t k = key.find('.');
    const std::string_view pattern_part = pattern.substr(0, p);
    const std::string_view key_part = key.substr(0, k);
    // A dotted metric name ("badpix_0.07") is the pattern's last part: the rest of the key must equal it.
    if (p == std::string_view::npos) return pattern_part == "*" ? k == std::string_view::npos : pattern == key;
    if (k == std::string_view::npos) return false;
    if (pattern_part != "*" && pattern_part != key_part) return false;
    pattern.remove_prefix(p + 1);
    key.remove_prefix(k + 1);
  }
}

}  // namespace

const MetricDescription* DescribeMetric(std::string_view dotted_key) {
  for (const MetricDescription& description : kDescriptions)
    if (Matches(description.key, dotted_key)) return &description;
  return nullptr;
}

std::string_view DescribeGroup(std::string_view group) {
  if (group == "depth") return "Depth against the true disparity";
  if (group == "segmentation") return "Superpixels";
  if (group == "decode_vs_truth") return "Decode against the ideal light field";
  if (group == "depth_maps") return "The depth maps themselves";
  return "";
}

std::string_view DescribeRegion(std::string_view part) {
  if (part == "all") return "whole view";
  if (part == "near_discontinuities") return "near depth edges";
  return "";
}

}  // namespace lfsp::report
