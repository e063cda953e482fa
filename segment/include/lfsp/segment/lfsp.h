#pragma once

#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/segment/params.h"
#include "lfsp/segment/plane.h"

namespace lfsp::segment {

struct LfspTimings {
  double lab_seconds = 0.0;
  double initial_seconds = 0.0;     // centre-view SLIC + plane fit
  double projection_seconds = 0.0;  // projection into all views + filling
  double refine_seconds = 0.0;      // block-coordinate descent (label sweeps + plane steps)
  double plane_seconds = 0.0;       // of which plane smoothing
  double carry_seconds = 0.0;       // the refined centre labels carried into the side views
  double total_seconds = 0.0;
};

struct LfspResult {
  Labels labels;              // one label per ray; every label is one centre-view superpixel projected to all views
  std::vector<Plane> planes;  // planes[k] of label k, centre-view coordinates
  int superpixels = 0;        // number of labels K (0 .. K-1)
  int iterations_run = 0;     // outer BCD iterations actually run
  long long label_moves = 0;  // rays that changed label during the BCD
  std::vector<long long> moves_per_iteration;
  std::vector<double> sweep_seconds;  // wall time of each label-move sweep of the BCD
  double noise_sigma = 0.0;           // estimated noise of the centre view (EstimateNoiseSigma)
  double presmooth = 0.0;             // colour smoothing used, px (after the automatic choice)
  LfspTimings timings;
};

// Segments the light field into light-field superpixels (Algorithm 1): SLIC of the centre view with colour, position
// and disparity; a slanted plane per superpixel; projection of every superpixel into all views (occlusion order by
// disparity, disoccluded rays filled from the background side); then the energy of Eq. 3 minimised by
// block-coordinate descent over boundary rays; last, the refined centre labels carried into the side views along
// the disparity wherever the centre view sees the ray (centre_carry.h). `disparity` is the centre-view disparity
// (docs/DESIGN.md convention).
// Throws lfsp::Error if the sizes disagree or a parameter is out of range.
LfspResult SegmentLightField(const LightField& light_field, const DisparityMap& disparity,
                             const LfspParams& params = {});

}  // namespace lfsp::segment
