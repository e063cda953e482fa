#pragma once

#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/params.h"
#include "lfsp/segment/plane.h"

namespace lfsp::segment {

// Inputs of the block-coordinate descent that do not change while it runs.
struct RefineInputs {
  const float* lab = nullptr;               // [v][u][y][x][3] CIELab of every ray
  const float* centre_disparity = nullptr;  // H x W, the input disparity of the centre view
  double disparity_range = 1.0;             // max d - min d of the centre disparity (> 0)
  int superpixels = 0;                      // K, labels 0 .. K-1
};

struct RefineReport {
  int iterations = 0;
  long long moves = 0;
  std::vector<long long> moves_per_iteration;
  std::vector<double> sweep_seconds;  // wall time of each label-move sweep
  double plane_seconds = 0.0;         // wall time of all plane-smoothing steps
  int occlusion_boundaries = 0;
  int hinge_boundaries = 0;
  int coplanar_boundaries = 0;
};

// Minimises Eq. 3 by block-coordinate descent (after SPS-Stereo): each outer iteration moves boundary rays of every
// view to the cheapest of their own and their 4-neighbours' labels (colour, position and, in the centre view,
// disparity against the candidate's slice and plane, plus the boundary term over the 80-neighbour clique with
// each candidate's own disparity), never splitting a slice within its view nor emptying a label's centre slice;
// then re-types the superpixel boundaries and re-fits the planes on the new centre view.
// Views are processed in four phases by angular parity (u mod 2, v mod 2): a view's 80-clique reaches only views of
// the other phases, so the views of one phase run in parallel without sharing any label they write (a band of rows
// at a time, for the cache).
RefineReport RefineLabels(const RefineInputs& inputs, const LfspParams& params, Labels& labels,
                          std::vector<Plane>& planes);

}  // namespace lfsp::segment
