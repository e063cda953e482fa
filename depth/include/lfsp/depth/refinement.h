#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/depth/cost_volume.h"

namespace lfsp::depth {

struct DisparityEstimate {
  DisparityMap disparity;
  DisparityMap confidence;  // in [0, 1]: how clearly the best label beats the best label not adjacent to it
};

// Winner-take-all per pixel, refined below the label step by fitting a parabola through the best label's cost and
// its two neighbours. Confidence = (c_other - c_best) / c_other, c_other being the lowest cost more than one label
// away from the best.
DisparityEstimate SelectDisparity(const CostVolume& cost, const std::vector<float>& disparities);

// The sub-label offset of the semi-global pass's labels, from the data cost where the aggregated one says nothing
// about it. On a textured surface a path reaches a label next to the best one by stepping from the best label's
// cost, so the aggregated cost there is about p1 per path above the best whatever the sub-label position, and the
// parabola through the aggregated costs lands too near the label: noise-free fronto-parallel strips of
// e2e/full_size read up to 0.016 px (a third of a label step) towards their nearest label, which for 80 labels over
// -2 .. 2 lies towards d = 0. So where, on either side of the best label b, what the paths add beyond the pixel's own
// data cost is at least `saturation` x p1 per path, the data costs of labels b - 1, b and b + 1 are summed over a
// window weighted exp(-|colour difference|^2 / (2 sigma^2)) by the centre view (as the weighted median's), and where
// that sum is lowest at b, the offset is the equiangular fit through the three (a truncated L1 cost rises linearly
// on both sides of its minimum, where a parabola would pull towards the label too). Elsewhere the aggregated
// parabola stays: where the paths carry the neighbours' data (weak texture) it is the better estimate (used
// everywhere, the data fit raised antinous's BadPix 0.07 from 5.71 to 6.08 % and the F01 two-horses chain's from
// 2.75 to 2.82 %). `p1` is the penalty the semi-global pass used (DepthResult::sgm).
struct SubLabelOptions {
  int radius = 3;  // window radius; 0 = off (the aggregated cost's parabola everywhere)
  float sigma = 0.05f;
  float saturation = 0.75f;
  float p1 = 0.0f;  // set by EstimateDepth from the penalties it used
};
void RefineSubLabelFromData(DisparityMap& disparity, const CostVolume& aggregated, const CostVolume& data,
                            const std::vector<float>& disparities, const cv::Mat& guide_rgb,
                            const SubLabelOptions& options = {});

// The weighted-median refinement: weights exp(-|colour difference|^2 / (2 sigma^2)) from the centre view, so depth
// edges stay on colour edges.
struct MedianOptions {
  int radius = 3;       // the fine window's radius (0 = no refinement at all): removes isolated outliers
  float sigma = 0.05f;  // colour scale of the weights (RGB in [0, 1])
  // A wide window (read every second pixel) corrects gross errors the fine one cannot reach: a thin occluder's
  // disparity spread over a flat region beside it by the semi-global pass. Its median replaces the fine one only
  // where the two differ by more than `wide_threshold` px, because over a slanted surface it is biased by the slope
  // times the radius (antinous: BadPix 0.07 5.70 -> 8.57 % if taken everywhere at radius 10).
  int wide_radius = 10;         // at most `radius` (e.g. 0) = off
  float wide_threshold = 0.5f;  // px per view step
};

// The fine window's weighted median of the disparity, or the wide window's where the two differ by more than
// `wide_threshold`.
void WeightedMedianRefine(DisparityMap& disparity, const cv::Mat& guide_rgb, const MedianOptions& options);

// Lowers the confidence near depth edges of the final disparity, where nearly all of depth's error lies (foreground
// fattening, issue 43): each value is multiplied by 1 - exp(-r^2 / (2 radius^2)), r being the distance to the nearest
// pixel of a jump of more than `jump` px per view step between 4-neighbours (0 on the jump itself). The cost margin
// alone ranks the edges' errors among the surfaces' small ones: the sparsification area on antinous fell from 1.43
// to 0.18 with this (oracle 0.056), and on every simulator scene with edges (BENCHMARKS.md, 2026-12-06).
struct EdgeConfidenceOptions {
  float jump = 0.2f;
  float radius = 2.5f;  // px
};
void LowerConfidenceNearDepthEdges(DisparityMap& confidence, const DisparityMap& disparity,
                                   const EdgeConfidenceOptions& options = {});

// Two passes of a 3 x 3 median over the confidence of a semi-global estimate. Its cost margin is read off the sum of
// eight path costs, and on noisy views (lenslet decodes) each path leaves streaks a pixel or two wide along its
// direction: the confidence of the real F01 frames was a cross-hatch of them at 0, 45, 90 and 135 degrees, which
// looked like a grid (issue 49). The medians remove such lines, and rank errors better too: on antinous the
// sparsification area above the oracle went 0.120 -> 0.092 (one pass 0.097, three 0.090; a 5 x 5 median 0.131 and
// Gaussian blurs 0.104 and worse, and they leave the streaks).
void RemoveConfidenceStreaks(DisparityMap& confidence);

}  // namespace lfsp::depth
