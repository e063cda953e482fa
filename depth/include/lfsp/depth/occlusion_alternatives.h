#pragma once

#include <opencv2/core/mat.hpp>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/depth/cost_volume.h"
#include "lfsp/depth/occlusion.h"

namespace lfsp::depth {

// Near an edge, a partial angular patch (OcclusionAlternatives) lets a background pixel beside an occluder, or in a
// gap between two, match on the views that see it. On a thin structure in front (a 2 px picket, a rail) the same
// patches mislead: the detail term's support reaches the background behind, which moves against the structure from
// view to view, so every patch pays at the structure's true disparity; and the views along the structure see it
// again at any disparity (their shifts run along it) while its surroundings line up at the background's. The
// cheapest patch then reads the background's disparity, and the structure is lost. Measured on the simulator's
// layers scene (9x9x512x512), its 2 px pickets: 4224 of their 10316 pixels read the background with every patch
// admitted, 806 with the whole patch only.
//
// So an alternative is refused at a pixel that looks like a thin structure in front of the disparity it prefers:
// judged on `whole_patch` (the disparity from the whole angular patch alone, which keeps thin structures), the
// pixel stands nearer than that disparity, and on both sides of it across the edge, within `reach` steps along the
// edge's normal, lies a pixel at that disparity or behind it (to within `margin`) whose colour differs from the
// pixel's by more than `colour_difference`
// (mean |dR|, |dG|, |dB|): the surface behind, seen beside the structure. A pixel in a gap between two occluders has
// its occluders on both sides instead, and its neighbours in the same gap share its colour, so its patches stay.
// Nor is the mixed pixel of an edge between two colours a structure: its colour is a blend of the two sides'
// (within `blend_difference`). Without that test the tile edges of the full-size Illum planes scene's checkered
// floor were taken for structures (1736 refusals, MSE x100 on its ideal light field 1.66 -> 2.72; with it, 80
// refusals and 1.67).
struct ThinStructureOptions {
  int reach = 4;                   // steps to each side across the edge; 0 = admit every alternative (the old rule)
  float margin = 0.3f;             // px per view step
  float colour_difference = 0.1f;  // measured on layers: 0.05-0.15 alike, 0.2 keeps half the loss, 0.3 all of it
  float blend_difference = 0.05f;  // layers: 0.03-0.05 alike; at 0.1 a picket's mixed pixels pass for blends
};

// Which labels a partial patch may stand in at. A pixel p at disparity d is hidden from view (du, dv) by a surface at
// disparity d' > d that lies (du, dv) (d' - d) away from it in the centre view (docs/DESIGN.md's shifts), so it can
// be hidden from some view only if a pixel q stands nearer than d by at least |q - p| / R, R the longest view offset:
// d < max over q of (D(q) - |q - p| / R), the occluder horizon. Above it every view sees the pixel, and a partial
// patch's lower cost is noise or a mixed edge pixel's, not an occlusion: the lower envelope of two halves then reads
// a thin bar nearer than it stands (the bars scene's 2 px bar at 0.9 px read 0.98) and spreads an occluder into
// the flat surface beside it. D is the whole patch's disparity, which keeps every occluder in front.
struct OccluderHorizonOptions {
  // Partial patches stand in at labels below the horizon plus this (px per view step); < 0 = at every label (no
  // horizon). Without slack the envelope's lower cost below the horizon, and not above it, pulls surfaces whose
  // disparity the whole patch reads a little too far further away still (HCI antinous' dark floor: BadPix 0.07 5.85
  // -> 8.71 %). Even with it, flat tiles that the whole patch misreads move so (the simulated planes floor's ideal
  // light fields lose about 2 points; BENCHMARKS.md, thirty-fourth session).
  float slack = 0.1f;
  // Pixels: D is first widened to its maximum over a disc of this radius, so that a whole-patch disparity read a
  // little too far next to an edge does not lower the horizon there.
  int widening = 2;
};

// The occluder horizon of `whole_patch` (see OccluderHorizonOptions) for views at most `longest_view_offset` view
// steps from the centre view: D widened, then max over q of (D(q) - dist(q, p) / longest_view_offset), dist the
// 8-neighbour chamfer distance (steps of 1 and sqrt 2; at most 8 % above the Euclidean, so the horizon is at most
// that much lower far from an occluder).
DisparityMap OccluderHorizon(const DisparityMap& whole_patch, double longest_view_offset, int widening);

// Lowers `cost` to each alternative's cost at every pixel where that alternative is admitted (see above), and there
// only at the labels below the occluder horizon (`horizon`, with its slack; every label when horizon.slack < 0);
// `whole_patch` is the disparity estimated from `cost` as given. `centre` is the CV_32FC3 centre view (what the
// occlusion map was detected on); `longest_view_offset` the longest offset of a view in the cost from the centre view,
// in view steps. Returns how many (pixel, alternative) pairs were refused.
int AdmitOcclusionAlternatives(CostVolume& cost, const OcclusionAlternatives& alternatives,
                               const DisparityMap& whole_patch, const std::vector<float>& disparities,
                               const OcclusionMap& occlusion, const cv::Mat& centre,
                               const ThinStructureOptions& options, const OccluderHorizonOptions& horizon,
                               double longest_view_offset);

}  // namespace lfsp::depth
