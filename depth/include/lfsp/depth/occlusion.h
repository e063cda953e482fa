#pragma once

#include <opencv2/core/mat.hpp>

namespace lfsp::depth {

// Angular sectors the non-centre views are binned into, by the direction of their offset from the centre view.
// A split index j (0..kSplits-1) divides the sectors into two halves of kSectors/2 consecutive sectors by a line
// through the angular centre: half A = sectors j .. j+kSectors/2-1, half B = the rest.
constexpr int kSectors = 16;
constexpr int kSplits = kSectors / 2;

// Sector of a view offset (du, dv) != (0, 0): sector s is centred on the direction s * 360/kSectors degrees,
// measured from +x towards +y (image axes, the same axes as the views' shifts).
int SectorOfOffset(int du, int dv);

// Split whose dividing line is parallel to an edge whose normal (the image gradient) points at `normal_radians`:
// the views on the gradient's side fall in one half, the others in the other half.
int SplitForEdgeNormal(double normal_radians);

// The pair of opposite sectors a and a + kSectors/2 (a in 0..kSectors/2-1) nearest the direction of an edge whose
// normal points at `normal_radians`: the views whose offsets run along the edge.
int AlongPairForEdgeNormal(double normal_radians);

struct OcclusionOptions {
  double canny_low = 20.0;  // Canny hysteresis thresholds (OpenCV, 3x3 Sobel, L2) on each 8-bit RGB channel
  double canny_high = 60.0;
  double blur_sigma = 1.0;  // Gaussian pre-smoothing of the centre view, pixels
  // The views along an edge (OcclusionMap::along) follow the structure tensor of the centre view without blur_sigma's
  // blur, over a Gaussian window of this sigma, at the edge pixel, rather than the smoothed gradient the split uses.
  // Inside a comb of 1 px teeth the 1 px blur leaves 0.7 % of the teeth's contrast and a Sobel kernel's central
  // differences none, so the edges Canny finds there belong to the background seen through the gaps and point anywhere:
  // the views along them were the wrong ones, and the gaps read as the teeth. Measured on the simulator's 9x9x512x512
  // ideal light fields (BadPix 0.07 % / MSE x100), smoothed gradient -> window 3 with no gate below: comb 3.02 / 7.30
  // -> 1.51 / 2.35 (its 1 px gaps 32 % -> 2 % wrong), occluders 3.73 / 3.32 -> 3.44 / 3.04, layers 2.98 / 2.51 -> 2.89
  // / 2.61, HCI antinous 5.71 / 5.44 -> 5.70 / 5.41. Windows 1.5 to 5 all gave comb 1.5-1.6 / 2.3-2.6.
  double along_window_sigma = 3.0;
  // Where the tensor's coherence is below this (gradients pointing several ways: corners, isotropic texture),
  // the views along come from the smoothed gradient as before. Without it the textureless checker floor of the
  // simulated F01 planes capture's ideal light field lost 2.45 -> 2.82 in MSE x100; gate 0.3 gives 2.50 there and
  // comb 1.49 / 2.36, occluders 3.50 / 3.11, layers 2.89 / 2.56, antinous 5.71 / 5.42 (gate 0.5: comb 1.56 / 2.52).
  double along_min_coherence = 0.3;
  // Pixels within this distance of an edge may be occluded in some views. 0 = automatic: the largest shift of the
  // background against an occluder between the centre and an outer view (AutomaticOcclusionRadius).
  double radius = 0.0;
};

// Pixels near centre-view edges (candidate occlusion boundaries) and, for each, the split of the angular patch
// whose dividing line follows the orientation of the nearest edge.
struct OcclusionMap {
  cv::Mat candidate;  // CV_8U, 255 = near an edge: use the better half of the views
  cv::Mat split;      // CV_8U, split index 0..kSplits-1 (meaningful where candidate)
  cv::Mat along;      // CV_8U, AlongPairForEdgeNormal of the nearest edge (meaningful where candidate)
  int Candidates() const;
};

// max(|u - uc|, |v - vc|) * (dmax - dmin), clamped to [2, kMaxAutomaticOcclusionRadius] pixels, plus twice the
// Gaussian presmoothing of the views: a background pixel this far from an occluder's edge is hidden in the outermost
// view on the occluder's side when the two lie at the ends of the disparity range, and presmoothing spreads the edge
// by about 2 sigma more. With half the shift and no blur term, a band of background next to occluders was matched
// on all views, where the occluder's edge, carried along with it, won: the horses of the F01 two-horses light
// fields grew by several pixels (BadPix 0.07 on the ideal light field 8.9 % -> 4.9 %; on its capture, presmoothed
// by 2.5 px, 15.3 % with the full shift alone, 9.9 % with the blur term).
// The cap: a real edge rarely separates the two ends of a wide range, and beyond it the half patch only discards
// views (antinous, range 6.1 over 9x9 views: 5.86 % at 12.2 px, 6.3 % at 24.4 px).
constexpr double kMaxAutomaticOcclusionRadius = 12.0;
double AutomaticOcclusionRadius(int nu, int nv, float disparity_min, float disparity_max, double presmooth_sigma = 0.0);

// The longest offset of a view of an nu x nv light field from its centre view, in view steps (a corner view's).
double LongestViewOffset(int nu, int nv);

// Wang et al.'s detector: Canny on each channel of the centre view, OR-ed; the split's orientation from the smoothed
// gradient at the edge pixel, the views along the edge from the local structure tensor there (along_window_sigma);
// every pixel within `radius` of an edge inherits the split and the views along of its nearest edge pixel.
OcclusionMap DetectOcclusionEdges(const cv::Mat& centre_rgb, const OcclusionOptions& options);

}  // namespace lfsp::depth
