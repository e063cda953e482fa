#include "lfsp/segment/lfsp.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "centre_carry.h"
#include "centre_slic.h"
#include "lab_image.h"
#include "lfsp/core/error.h"
#include "lfsp/core/noise.h"
#include "lfsp/core/stopwatch.h"
#include "planes.h"
#include "refine.h"
#include "warp.h"

namespace lfsp::segment {
namespace {

// The centre disparity with non-finite samples replaced by the median, and its range (at least 1e-3).
cv::Mat CleanDisparity(const DisparityMap& disparity, double& range) {
  cv::Mat clean = disparity.Mat().clone();
  std::vector<float> finite;
  finite.reserve(clean.total());
  for (auto it = clean.begin<float>(); it != clean.end<float>(); ++it) {
    if (std::isfinite(*it)) finite.push_back(*it);
  }
  if (finite.empty()) throw Error("LFSP: the disparity map has no finite value");
  const auto [lo, hi] = std::minmax_element(finite.begin(), finite.end());
  range = std::max(1e-3, static_cast<double>(*hi - *lo));
  auto middle = finite.begin() + static_cast<std::ptrdiff_t>(finite.size() / 2);
  std::nth_element(finite.begin(), middle, finite.end());
  const float median = *middle;
  for (auto it = clean.begin<float>(); it != clean.end<float>(); ++it) {
    if (!std::isfinite(*it)) *it = median;
  }
  return clean;
}

// FillHoles spreads the labels that landed in a view; when none landed (every plane disparity non-finite, as fitted to
// a map of 3e38, or so large that every ray leaves the view, as after a refocus by 1e9) the view kept ForwardWarp's -1
// everywhere, and the refinement used -1 as a superpixel index: it wrote before the start of its per-view slice
// table, corrupting the heap (issue 45). Such rays take the centre label at their own position (disparity 0), so
// every ray holds a superpixel, as the refinement requires.
void TakeCentreLabelsWhereNothingLanded(const cv::Mat& centre_labels, std::int32_t* view_labels) {
  const std::int32_t* centre = centre_labels.ptr<std::int32_t>(0);
  for (std::size_t i = 0; i < centre_labels.total(); ++i)
    if (view_labels[i] < 0) view_labels[i] = centre[i];
}

// Algorithm 1, lines 3-14: every centre-view superpixel projected into every view along its plane, front-most
// first, then the rays nothing projects to filled from the background side of their epipolar line.
void ProjectSuperpixels(const cv::Mat& centre_labels, const std::vector<Plane>& planes, Labels& labels) {
  const LightFieldShape& shape = labels.shape();
  const ViewIndex centre = shape.Centre();
  cv::Mat plane_disparity(centre_labels.size(), CV_32F);
  float max_abs = 0.0f;
  for (int y = 0; y < centre_labels.rows; ++y) {
    for (int x = 0; x < centre_labels.cols; ++x) {
      const float d = static_cast<float>(planes[static_cast<std::size_t>(centre_labels.at<int>(y, x))].AtCentre(x, y));
      plane_disparity.at<float>(y, x) = d;
      max_abs = std::max(max_abs, std::abs(d));
    }
  }
  const int views = static_cast<int>(shape.Views());
#pragma omp parallel for schedule(dynamic)
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    std::int32_t* out = labels.ViewData(view);
    if (view == centre) {
      std::copy(centre_labels.ptr<int>(0), centre_labels.ptr<int>(0) + centre_labels.total(), out);
      continue;
    }
    const int du = view.u - centre.u, dv = view.v - centre.v;
    std::vector<float> depth(shape.ViewPixels());
    ForwardWarp(centre_labels.ptr<std::int32_t>(0), plane_disparity.ptr<float>(0), shape.width, shape.height, du, dv,
                out, depth.data());
    FillHoles(out, depth.data(), shape.width, shape.height, du, dv, FillReach(max_abs, du, dv));
    TakeCentreLabelsWhereNothingLanded(centre_labels, out);
  }
}

}  // namespace

LfspResult SegmentLightField(const LightField& light_field, const DisparityMap& disparity, const LfspParams& params) {
  Validate(params);
  const LightFieldShape& shape = light_field.shape();
  if (light_field.empty()) throw Error("LFSP: the light field is empty");
  RequireSuperpixelSizeFits(params.size, shape, "LFSP");
  if (disparity.width() != shape.width || disparity.height() != shape.height) {
    throw Error("LFSP: disparity map is " + std::to_string(disparity.width()) + "x" +
                std::to_string(disparity.height()) + " but the views are " + std::to_string(shape.width) + "x" +
                std::to_string(shape.height));
  }
  const int saved_threads = omp_get_max_threads();
  if (params.threads > 0) omp_set_num_threads(params.threads);
  const Stopwatch total;
  Stopwatch step;
  LfspResult result;

  LabRays lab = LabOfLightField(light_field);
  result.noise_sigma = EstimateNoiseSigma(light_field.View(shape.Centre()));
  result.presmooth = params.presmooth < 0.0 ? PresmoothForNoise(result.noise_sigma) : params.presmooth;
  if (result.presmooth > 0.0) SmoothLabViews(lab, shape, result.presmooth);
  result.timings.lab_seconds = step.Lap();

  double range = 1.0;
  const cv::Mat centre_disparity = CleanDisparity(disparity, range);
  const ViewIndex centre = shape.Centre();
  cv::Mat centre_labels =
      CentreSuperpixels(LabView(lab, shape, centre), centre_disparity, range, params, result.superpixels);
  result.planes = FitPlanes(centre_labels, result.superpixels, centre_disparity, params.inlier_threshold);
  result.timings.initial_seconds = step.Lap();

  result.labels = Labels(shape, Labels::Unfilled{});  // ProjectSuperpixels writes every ray
  ProjectSuperpixels(centre_labels, result.planes, result.labels);
  result.timings.projection_seconds = step.Lap();

  RefineInputs inputs;
  inputs.lab = lab.data();
  inputs.centre_disparity = centre_disparity.ptr<float>(0);
  inputs.disparity_range = range;
  inputs.superpixels = result.superpixels;
  const RefineReport report = RefineLabels(inputs, params, result.labels, result.planes);
  result.iterations_run = report.iterations;
  result.label_moves = report.moves;
  result.moves_per_iteration = report.moves_per_iteration;
  result.sweep_seconds = report.sweep_seconds;
  result.timings.plane_seconds = report.plane_seconds;
  result.timings.refine_seconds = step.Lap();
  // The side views' label moves drift from the centre's superpixels next to thin occluders (centre_carry.h); the
  // refined centre view is carried back into them along the disparity. On the simulator's comb, self-similarity
  // 1.46 -> 0.65 px (reference 0.77), boundary recall 0.787 -> 0.816 (BENCHMARKS.md, twentieth session).
  CarryCentreToSideViews(centre_disparity, result.planes, result.labels);
  result.timings.carry_seconds = step.Lap();
  // No per-view connectivity clean-up: a superpixel's slice in a side view may be cut in two by something in front
  // of it that the centre view sees beside it, and merging the smaller piece into a neighbour (as a clean-up did)
  // breaks the consistency (self-similarity on the simulator's occluders 0.845 -> 0.898 px, reference 0.814, before
  // the carry existed). The centre view's slices are connected by construction: SLIC's own clean-up, and label
  // moves never split a slice within its view.
  result.timings.total_seconds = total.Seconds();
  if (params.threads > 0) omp_set_num_threads(saved_threads);
  return result;
}

}  // namespace lfsp::segment
