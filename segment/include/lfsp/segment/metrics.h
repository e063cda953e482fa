#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::segment {

// Superpixel metrics. The 2D forms take one view (CV_32SC1 label maps of equal size); the 4D forms score every view
// and average over views, which is how the light-field papers report them (Khan et al. ICCV 2019, LFSP TIP 2020).
// Ground-truth pixels labelled < 0 (unlabelled) are ignored by UE and ASA.

// Boundary recall: the share of ground-truth boundary pixels (a 4-neighbour has another label) that have a
// superpixel boundary pixel within `tolerance` pixels (chessboard distance). Returns -1 if `gt` has no boundary.
double BoundaryRecall2D(const cv::Mat& labels, const cv::Mat& gt, int tolerance = 2);
// Neubert-Protzel corrected under-segmentation error: (1/N) sum_i sum_j min(|S_j n G_i|, |S_j - G_i|).
double UndersegmentationError2D(const cv::Mat& labels, const cv::Mat& gt);
// The per-region variant of Khan et al.: for each ground-truth region G_i, sum over superpixels S_j touching it of
// |S_j - G_i| if most of S_j lies in G_i, else |S_j n G_i|, divided by |G_i|; the mean over regions.
double RegionUndersegmentationError2D(const cv::Mat& labels, const cv::Mat& gt);
// Achievable segmentation accuracy: (1/N) sum_j max_i |S_j n G_i|.
double AchievableSegmentationAccuracy2D(const cv::Mat& labels, const cv::Mat& gt);
// Compactness (Schick et al.): sum_j (|S_j| / N) 4 pi |S_j| / L_j^2, L_j the perimeter in pixel edges (image border
// included).
double Compactness2D(const cv::Mat& labels);

double BoundaryRecall(const Labels& labels, const Labels& gt, int tolerance = 2);
double UndersegmentationError(const Labels& labels, const Labels& gt);
double RegionUndersegmentationError(const Labels& labels, const Labels& gt);
double AchievableSegmentationAccuracy(const Labels& labels, const Labels& gt);

// The three overlap scores above from one count of each view's overlaps (each function alone counts them anew,
// 0.15 s apiece on a 9x9 Illum segmentation): the same values.
struct OverlapScores {
  double undersegmentation_error = -1.0;
  double region_undersegmentation_error = -1.0;
  double achievable_segmentation_accuracy = -1.0;
};
OverlapScores ScoreOverlaps(const Labels& labels, const Labels& gt);
double Compactness(const Labels& labels);

// Effective label ratio (Eq. 11): labels present in the centre view / labels present anywhere.
double EffectiveLabelRatio(const Labels& labels);
// The same from counts a caller has already made: centre labels over all labels, 0 without labels.
double EffectiveLabelRatio(int centre_label_count, int label_count);

// Distinct labels in the centre view and in the whole light field.
int CentreLabelCount(const Labels& labels);
int LabelCount(const Labels& labels);

// The disparity of every ray from a centre-view disparity map: forward-projected with occlusion order, holes filled
// from the background side of the epipolar line. Views in camera order (cam = v * nu + u).
std::vector<DisparityMap> PropagateDisparity(const DisparityMap& centre, const LightFieldShape& shape);

// Per view (camera order) and label: the sums of x and y of the label's rays carried to the centre view by their
// disparity, and the ray count, as [cam][label][3]; `label_count` is the largest label + 1 (0 if none). With
// `in_frame_only`, rays landing outside the centre view's frame are left out. Both self-similarity definitions
// (here and khan_metrics.h) read their centroids from it.
std::vector<double> CarriedCentroidSums(const Labels& labels, const std::vector<DisparityMap>& view_disparity,
                                        bool in_frame_only, std::size_t& label_count);
// Both variants of CarriedCentroidSums from one pass over the rays (the evaluation scores both).
struct CarriedCentroids {
  std::vector<double> all;       // in_frame_only = false
  std::vector<double> in_frame;  // in_frame_only = true
  std::size_t label_count = 0;
};
CarriedCentroids CarriedCentroidSumsBoth(const Labels& labels, const std::vector<DisparityMap>& view_disparity);
// SelfSimilarity from sums CarriedCentroidSums made (either variant).
double SelfSimilarityOfSums(const std::vector<double>& sums, std::size_t label_count, const LightFieldShape& shape);
// LFSP self-similarity (Eqs. 8-10): every slice projected to the centre view with the ground-truth disparity of its
// rays, the distance of its centroid from the centre slice's centroid, averaged over the views where the label
// appears, then over labels present in the centre view and in at least one other view. Pixels.
// With `in_frame_only`, rays whose projection falls outside the centre view's frame (scene points the centre view
// does not see, at the image borders) are left out; the paper's Eq. 8 counts them (the default).
double SelfSimilarity(const Labels& labels, const std::vector<DisparityMap>& view_disparity,
                      bool in_frame_only = false);

// The reference for self-similarity: the centre view's labels carried to every view by the ground truth. A ray
// whose scene point the centre view sees (its disparity agrees, within 0.25 px, with the centre pixel it projects
// to) takes that pixel's label; rays the centre view does not see (uncovered behind an occluder, or outside its
// frame) are filled from the background side of their epipolar line, as LFSP's projection fills them. It is a
// perfectly view-consistent segmentation with the same centre superpixels, so its self-similarity is what
// occlusions and the image border cost on their own under Eq. 8.
Labels CarryCentreLabels(const Labels& labels, const DisparityMap& centre_disparity,
                         const std::vector<DisparityMap>& view_disparity);

// For segmentations made view by view (no label links views): renames every superpixel of every side view to the
// centre-view label it overlaps most once its pixels are projected to the centre view with `view_disparity` (a
// superpixel with no overlap keeps a fresh label). This follows per-view superpixels across views as generously as
// possible, so their self-similarity can be compared with LFSP's.
Labels FollowToCentre(const Labels& labels, const std::vector<DisparityMap>& view_disparity);

// Labels per pixel (Khan et al.): every centre pixel followed into each view where it is visible (the view's
// disparity agrees within 0.5 px); 1 + the mean number of distinct labels met there that are absent from the centre
// labels of its 3x3 neighbourhood. 1 for a perfectly view-consistent segmentation.
double LabelsPerPixel(const Labels& labels, const DisparityMap& centre_disparity,
                      const std::vector<DisparityMap>& view_disparity);

}  // namespace lfsp::segment
