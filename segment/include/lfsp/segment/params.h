#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/core/light_field.h"

namespace lfsp::segment {

// Parameters of the LFSP segmentation (Zhu, Zhang, Wang, TIP 2020). The weights default to the paper's Table II.
//
// The energy of one ray p in view (u, v) with candidate label k is (Eq. 3, per ray):
//   E_c  = |Lab(p) - c_k^{uv}|^2 / colour_scale^2                    colour against the slice's mean colour
//   E_p  = |p - mu_k^{uv}|^2 / size^2                                position against the slice's centroid
//   E_d  = ((d(p) - dhat(p, pi_k)) / (max d - min d))^2              centre view only (Eq. 4)
//   E_b  = sum over the 80-neighbour clique q of pen(q) [s(q) != k] / 8   (Eq. 7; pen = spatial/angular/mixed)
//   E    = E_c + lambda_p E_p + lambda_d E_d + lambda_b E_b
// The two normalisations the paper leaves implicit are explicit here: colour is measured in units of
// `colour_scale` Lab units (lambda_p behaves like SLIC's compactness m = colour_scale sqrt(lambda_p), so the
// defaults give SLIC's usual m = 10), and the clique sum is divided by 8, so one whole ring of differing spatial
// neighbours costs E_pen_s. Where the clique is cut (image border, edge views) the counts are rescaled to the full
// clique.
// The planes minimise lambda_d sum E_d + lambda_s sum E_s (Eq. 5) with boundary types occlusion / hinge / coplanar.
struct LfspParams {
  int size = 20;                  // superpixel size: grid step of the centre-view seeds, pixels
  double lambda_p = 2.0;          // position weight (Table II)
  double lambda_d = 50.0;         // disparity weight (Table II)
  double lambda_s = 0.01;         // plane smoothness weight (Table II)
  double lambda_b = 1.0;          // boundary weight (Table II)
  double pen_spatial = 1.0;       // E_pen_s, spatial neighbours (Table II)
  double pen_mixed = 0.7;         // E_pen_m, mixed neighbours (Table II)
  double pen_angular = 4.0;       // E_pen_a, angular neighbours (Table II)
  double colour_scale = 7.0711;   // Lab distance worth one unit of energy (10/sqrt2: lambda_p = 2 is SLIC m = 10)
  int slic_iterations = 10;       // iterations of the initial centre-view SLIC (colour + position + disparity)
  int iterations = 10;            // outer block-coordinate-descent iterations (label moves + plane smoothing)
  int plane_iterations = 10;      // inner plane-smoothing iterations (boundary typing + plane refit) per outer one
  double inlier_threshold = 0.5;  // |d - plane| (px/view) above which a centre pixel does not pull its plane
  double hinge_penalty = 0.05;    // constant cost of a hinge boundary (px^2, SPS's 5 scaled to light-field disparities)
  double occlusion_penalty = 0.25;  // cost of an occlusion boundary (px^2; SPS 15)
  double impossible_penalty = 0.5;  // added when the claimed occluder is behind along the boundary (px^2; SPS 30)
  double convergence = 1e-5;        // stop when fewer than this fraction of rays changed label in an outer iteration
  // Gaussian smoothing (px) of the colours the energy compares, against noise (low light): < 0 = chosen from the
  // centre view's estimated noise (none on clean views, up to 1.5 px), 0 = off.
  double presmooth = -1.0;
  int threads = 0;  // OpenMP threads; 0 = default
};

// The colour smoothing chosen for a noise level (EstimateNoiseSigma): none up to kCleanNoiseLevel, then 0.4 px per 0.01
// of noise, at most 1.5 px. On planes (9x9 views of 256x256, true disparity, Gaussian noise 0.08 per channel, which
// reads 0.054, so 1.5 px): SS 1.83 -> 0.95 px, UE 0.126 -> 0.016, BR 0.932 unchanged (measured before the side views
// were carried from the centre view, centre_carry.h, which cuts the unsmoothed SS too).
double PresmoothForNoise(double noise_sigma);

nlohmann::json ToJson(const LfspParams& params);
// What a segmentation bundle records in metadata["lfsp_segment"] (read back by `lfsp evaluate segmentation`): the
// parameters and where the disparity came from.
nlohmann::json SegmentationRecord(const LfspParams& params, const std::string& disparity_source);
// Reads the fields present in `json` over the defaults; throws lfsp::Error naming `where` on a bad value.
LfspParams ParamsFromJson(const nlohmann::json& json, const std::string& where = "parameters");
// Throws lfsp::Error naming the parameter when a value is out of range.
void Validate(const LfspParams& params);

// Throws lfsp::Error naming `what` unless a superpixel grid step of `size` fits views of `shape`: at least 2 and at
// most the shorter view side (OpenCV's SLIC and LSC crash on steps beyond twice it; one superpixel per view is the
// most a segmentation can mean). Every superpixel method calls it, and the commands before any work.
void RequireSuperpixelSizeFits(int size, const LightFieldShape& shape, const std::string& what);

}  // namespace lfsp::segment
