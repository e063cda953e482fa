#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp::depth {

// The pixels along an occlusion edge whose colour is mostly the farther surface's, given back to it.
//
// A pixel that an occluder's edge crosses holds a mixture of the two surfaces' colours, and the angular patch at the
// occluder's disparity sees that same mixture in every view (the edge moves with the occluder), so the cost prefers
// the nearer surface even where most of the pixel, and its centre, is the farther one: the foreground reads about a
// pixel fat (issue 43's fattening). Where the disparity steps between 4-neighbours p (nearer) and q (farther), the
// colours `depth` pixels into each side stand for the two surfaces, F behind p and B beyond q, and p's share of F
// is estimated twice: from its RGB as a point between B and F, and from its chromaticity (RGB over its sum) between
// theirs. Shading darkens a surface without changing its chromaticity, so a rim that turns away from the light (the
// bust of HCI antinous) keeps a chromaticity share near 1 and stays; a mixed pixel moves in both. p takes q's
// disparity when the larger of the two shares is below `max_share`, the two sides' colours differ enough in both
// (RGB and chromaticity), and both sides are even in disparity over `depth` pixels. Repeated for `rounds` rounds
// (the second pixel of a 2 px fattening becomes an edge pixel once the first has moved), each on the previous
// round's disparity. Measured on the simulator's scenes, antinous and the full-size chain (BENCHMARKS.md,
// forty-third session).
struct MixedEdgeOptions {
  float max_share = 0.4f;           // 0 = off: the share of the nearer side's colour below which a pixel moves
  float jump = 0.2f;                // px per view step between p and q that counts as an occlusion edge
  int depth = 2;                    // pixels into each side whose mean colour stands for it
  float rgb_separation = 0.05f;     // least RGB distance between the two sides' colours (samples in [0, 1])
  float chroma_separation = 0.05f;  // least distance between their chromaticities
  int rounds = 3;
};

// Moves the mixed edge pixels of `disparity` to the farther side, as above; returns how many moves were made over
// all rounds (a pixel that moves along two directions in one round counts twice). A foreground strip no wider than
// `depth` pixels has no even side behind its edge pixels, so thin structures never move. `guide_rgb`: the centre view,
// CV_32FC3, the disparity's size. Non-finite disparities neither move nor stand for a side.
int ReassignMixedEdgePixels(DisparityMap& disparity, const cv::Mat& guide_rgb, const MixedEdgeOptions& options = {});

}  // namespace lfsp::depth
