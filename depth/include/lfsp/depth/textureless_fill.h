#pragma once

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"

namespace lfsp::depth {

// The disparity of textureless pixels, interpolated from the textured pixels around them.
//
// Inside a region of flat colour the cost volume says nothing, and the semi-global pass fills it with steps of one
// label placed by chance: a slanted floor of flat checker tiles reads as a staircase (the simulator's `spheres`
// floor). The fill solves
//   min_x  sum_i c_i (x_i - d_i)^2 + smoothness * sum_{i~j, |d_i - d_j| <= jump} (x_i - x_j)^2
// over the 4-neighbour pairs, d being the disparity given and c_i = e_i / (e_i + texture_scale^2) weighing a pixel's
// own estimate by its texture (e_i: the centre view's squared colour gradient summed over channels, 3 x 3 mean).
// Textured pixels (c near 1 against a smoothness of 1e-3) keep their disparity; a flat region takes the harmonic
// interpolation of the textured pixels around it, which is exact on a plane; no pair across a depth step is mixed,
// so a depth edge between two objects of one colour stays. It cannot mend what the textured rim itself reads wrong:
// on the simulator's lenslet decodes, whose blurred tile edges read the same steps as the tiles, it moves no
// disparity by more than 0.01 px. A non-finite disparity is left as it is and mixed with nothing.
struct TexturelessFillOptions {
  float smoothness = 1e-3f;     // 0 = off
  float texture_scale = 0.02f;  // colour gradient (per px, RGB in [0, 1]) at which a pixel's own disparity weighs 1/2
  float jump = 0.2f;            // px per view step: neighbours that differ more are not mixed (depth edges)
};

// Replaces `disparity` by an approximation of the minimum above: conjugate gradients preconditioned by the diagonal
// on a coarse-to-fine pyramid of 2 x 2 blocks, each level started from the coarser one's solution and given at most
// 60 steps (fewer once no step moves a value by 1e-5 px). Within 3e-3 px of the exact minimum where flat regions
// are 96 px wide (refinement_test.cc); on the simulator's spheres (512 x 512) 0.8 % of the pixels are more than
// 1e-3 px from it and 0.04 % more than 0.01 px (at most 0.05). `guide_rgb`: the centre view, CV_32FC3 in [0, 1],
// the disparity's size.
void FillTexturelessDisparity(DisparityMap& disparity, const cv::Mat& guide_rgb,
                              const TexturelessFillOptions& options = {});

}  // namespace lfsp::depth
