#pragma once
// Superpixel metrics as the de-facto standard evaluation defines them: Khan et al., "View-consistent 4D light field
// superpixel segmentation" (ICCV 2019), whose evaluation code (brownvc/lightfieldsuperpixels, eval/) produced the
// tables most light-field superpixel papers compare against. Reported beside metrics.h's so that lfsp's figures can
// stand next to published ones. Where the two differ:
//
// - Self-similarity: the mean over every (label, view) pair, the centre view's own zeros included, of the distance
//   between the label's centroid in that view (its pixels carried to the centre view by their disparity) and its
//   centre-view centroid. metrics.h averages per label over the other views first (LFSP Eqs. 8-10).
// - Labels per pixel: every view's pixels are carried to the centre view (rounded); where several land on one pixel
//   the front one is kept; then each centre pixel counts the views whose carried label is absent from its 3x3
//   neighbourhood, a view that carries nothing to it counting as well (so disocclusions count). 1 + the mean count.
//   metrics.h follows each centre pixel into the views where it is visible instead.
// - Boundary recall: boundaries are where the Sobel gradient of the label map (replicated border) is non-zero, a
//   band about two pixels wide on both sides of every label change, in both maps; tolerance 2 (chessboard). The
//   share of ground-truth boundary pixels with a boundary pixel of ours within it, averaged over views.
//   metrics.h marks only pixels with a 4-neighbour of another label.
// - Achievable accuracy: each superpixel gets one object label for the whole light field (the one it overlaps most
//   in any single view), then the share of rays whose object is right, averaged over views. metrics.h's ASA lets a
//   superpixel take its best object in each view separately.
// - Under-segmentation error: Khan's is metrics.h's RegionUndersegmentationError (identical when every ray has a
//   ground-truth label; metrics.h leaves out rays labelled < 0).
// - Size: the mean over centre-view superpixels of the square root of their area.
//
// One deliberate difference: where Khan's code keeps the ray of smallest |disparity| as the front one (right for the
// disparity sign of the old HCI files it reads), this keeps the front ray by lfsp's convention (larger disparity is
// nearer), which is what the metric means.
// Disparity maps are per view (PropagateDisparity of the centre map), in camera order; ray (x, y) of view (u, v)
// lands in the centre view at (x + (u - uc) d, y + (v - vc) d).

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::segment {

double KhanSelfSimilarity(const Labels& labels, const std::vector<DisparityMap>& view_disparity);
// KhanSelfSimilarity from CarriedCentroidSums's sums (in_frame_only = false).
double KhanSelfSimilarityOfSums(const std::vector<double>& sums, std::size_t label_count, const LightFieldShape& shape);
double KhanLabelsPerPixel(const Labels& labels, const std::vector<DisparityMap>& view_disparity);
double KhanBoundaryRecall(const Labels& labels, const Labels& gt);
double KhanAchievableAccuracy(const Labels& labels, const Labels& gt);
double KhanAverageSize(const Labels& labels);

// Every Khan metric the inputs allow: {"size", "self_similarity", "labels_per_pixel"} with view disparities,
// {"boundary_recall", "undersegmentation_error", "achievable_accuracy"} with ground-truth labels. Khan's
// undersegmentation error is RegionUndersegmentationError, and a caller that has it, or the self-similarity (from
// CarriedCentroidSumsBoth), already passes it in.
nlohmann::json ScoreKhan(const Labels& labels, const Labels* gt_labels,
                         const std::vector<DisparityMap>* gt_view_disparity,
                         std::optional<double> region_undersegmentation_error = std::nullopt,
                         std::optional<double> self_similarity = std::nullopt);

}  // namespace lfsp::segment
