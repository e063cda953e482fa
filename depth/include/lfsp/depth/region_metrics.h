#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "lfsp/core/light_field.h"
#include "lfsp/depth/metrics.h"

namespace lfsp::depth {

// The HCI benchmark's three evaluation regions (Honauer et al., ACCV 2016): pixels near depth discontinuities, on
// planar surfaces, and on smooth non-planar surfaces. CV_8U maps of the ground truth's size, 255 = in the region.
struct EvaluationMasks {
  cv::Mat discontinuities;
  cv::Mat planes;
  cv::Mat smooth_surfaces;
  // Where each came from: "file <path>" or "derived from the ground truth".
  std::string discontinuities_source, planes_source, smooth_surfaces_source;
};

// Options of the derived regions (used where a scene has no mask files).
struct MaskOptions {
  // A surface is planar where the Frobenius norm of the ground truth's Hessian (px per view step per pixel^2) is
  // below this: float rendering noise on a plane stays orders of magnitude under it, the gentlest curved surface
  // of the simulator above it.
  double plane_curvature = 1e-4;
};

// The regions derived from the ground truth alone: discontinuities as DiscontinuityRegion (jump and radius from
// `options`); planes where the ground truth's Hessian norm is below `plane_curvature`; smooth surfaces everywhere
// else that is finite and not near a discontinuity. Planes and smooth surfaces never overlap the discontinuities.
EvaluationMasks DeriveEvaluationMasks(const DisparityMap& gt, const MetricOptions& options,
                                      const MaskOptions& mask_options = {});

// The regions of a scene folder (the HCI benchmark's mask_discontinuities.png, mask_planes.png and
// mask_smooth_surfaces.png, any nonzero pixel inside), each replaced by its derived version when the file is absent.
// A mask an integer factor larger than the ground truth (the benchmark's high-resolution masks) is reduced to it:
// a low-resolution pixel is near a discontinuity if any of its pixels is, and on a plane or smooth surface only if
// all of them are. Throws lfsp::Error naming the file when a mask cannot be read or has another size.
EvaluationMasks ReadEvaluationMasks(const std::filesystem::path& folder, const DisparityMap& gt,
                                    const MetricOptions& options, const MaskOptions& mask_options = {});

// The benchmark's bumpiness: 100 x the mean over `region` (inside the evaluation frame) of min(0.05, |H|_F), where H
// is the Hessian of (algo - gt), each derivative taken with the normalised Scharr operator (3, 10, 3) / 32 x (1, 0,
// -1), so that a unit ramp has a unit derivative. Pixels whose Hessian is not finite are left out. NaN for an empty
// region.
double Bumpiness(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary = 15);

// Fattening index: of the pixels in `region` (inside the frame) that are bad at 0.07 px, the percentage that read
// nearer than the truth (algo > gt: larger disparity is nearer in the HCI convention). NaN when none is bad.
double FatteningIndex(const DisparityMap& algo, const DisparityMap& gt, const cv::Mat& region, int boundary = 15);

// The sparsification curve (metrics.h) of a confidence map: larger confidence = trusted first.
Sparsification SparsificationOf(const DisparityMap& algo, const DisparityMap& gt, const DisparityMap& confidence,
                                int boundary = 15);

// Every figure of DepthEvaluation over the given regions, and the sparsification of `confidence` when given.
DepthEvaluation EvaluateDisparity(const DisparityMap& algo, const DisparityMap& gt, const MetricOptions& options,
                                  const EvaluationMasks& masks, const DisparityMap* confidence = nullptr);

}  // namespace lfsp::depth
