#include "truth_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/core.hpp>

#include "lfsp/core/channel_gains.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/view_crop.h"
#include "lfsp/core/visualize.h"
#include "lfsp/depth/metrics.h"

namespace lfsp::pipeline {
namespace {

// Per pixel, the mean over channels of |gain_c * decoded - truth|, each channel's gain fitted by least squares.
// Both are views of a light field: one contiguous CV_32FC3 block each, read in place.
cv::Mat CentreError(const cv::Mat& decoded, Transfer decoded_transfer, const cv::Mat& truth, Transfer truth_transfer) {
  const int pixels = decoded.rows * decoded.cols;
  const float* a = decoded.ptr<float>();
  const float* b = truth.ptr<float>();
  const std::array<double, 3> gain = FitChannelGains(decoded, decoded_transfer, truth, truth_transfer);
  cv::Mat error(decoded.rows, decoded.cols, CV_32FC1);
  float* e = error.ptr<float>();
  for (int p = 0; p < pixels; ++p) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c)
      sum += std::abs(gain[static_cast<std::size_t>(c)] * LinearSample(a[3 * p + c], decoded_transfer) -
                      LinearSample(b[3 * p + c], truth_transfer));
    e[p] = static_cast<float>(sum / 3.0);
  }
  return error;
}

cv::Mat ColourMapped(const cv::Mat& values, float top) {
  DisparityMap map(values.cols, values.rows);
  values.copyTo(map.Mat());
  return ColourMapDisparity(map, DisparityRange{0.0f, top});
}

// The pixels farther than `margin` from every depth edge of the truth (a step of more than 0.1 px per view step
// between neighbours), where a view differs from the centre view by a shift alone. The margin is the largest parallax
// across the scene's depth range between the centre view and the outermost one, plus 2 px, at most 16.
struct DepthEdgeMask {
  cv::Mat mask;  // empty: no mask (no truth, or it would leave under a quarter of the pixels)
  int margin = 0;
};
DepthEdgeMask AwayFromDepthEdges(const std::optional<DisparityMap>& disparity, int half_views) {
  if (!disparity) return {};
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(disparity->Mat(), &low, &high);
  if (!std::isfinite(low) || !std::isfinite(high)) return {};
  const int margin = std::min(16, static_cast<int>(std::ceil(half_views * (high - low))) + 2);
  cv::Mat mask;
  cv::bitwise_not(depth::DiscontinuityRegion(*disparity, 0.1, margin), mask);
  if (4 * static_cast<std::size_t>(cv::countNonZero(mask)) < mask.total()) return {};
  return {mask, margin};
}

}  // namespace

TruthComparison CompareWithTruth(const LightField& decoded, const std::filesystem::path& truth,
                                 const std::optional<DisparityMap>& truth_disparity) {
  TruthComparison comparison;
  const LightFieldShape& shape = decoded.shape();
  comparison.nu = shape.nu;
  comparison.nv = shape.nv;
  const DepthEdgeMask away = AwayFromDepthEdges(truth_disparity, std::max(comparison.nu, comparison.nv) / 2);
  comparison.depth_edge_margin_px = away.margin;
  ViewRegistration& registration = comparison.registration;
  registration.views.resize(shape.Views());
  const ViewIndex centre = shape.Centre();
  // The decode may hold only the central views of the truth's grid (the pipeline decodes the views it keeps).
  const ViewIndex first = CentralViewBlock(ReadBundleShape(truth), shape.nu).first;
  for (int v = 0; v < shape.nv; ++v) {
    BundleParts row_of_views;
    row_of_views.views = ViewBlock{{first.u, first.v + v}, shape.nu, 1};
    row_of_views.disparity = false;
    row_of_views.labels = false;
    const LightField row = ReadBundle(truth, row_of_views).light_field;
    RegisterBlock(decoded, row, ViewIndex{0, v}, TruthComparison::kRegisteredWeight, 20, away.mask, registration);
    if (v == centre.v)
      comparison.centre_error =
          CentreError(decoded.View(centre), decoded.transfer, row.View(ViewIndex{centre.u, 0}), row.transfer);
  }
  CountRegistered(registration);
  const double mean_square = cv::mean(comparison.centre_error.mul(comparison.centre_error))[0];
  comparison.centre_rms = std::sqrt(mean_square);
  comparison.centre_psnr_db = mean_square > 0.0 ? -10.0 * std::log10(mean_square) : 99.0;
  return comparison;
}

nlohmann::ordered_json ToJson(const TruthComparison& comparison) {
  nlohmann::ordered_json views = nlohmann::ordered_json::array();
  for (const ViewShift& entry : comparison.registration.views) {
    if (!entry.registered) continue;
    views.push_back({{"u", entry.view.u},
                     {"v", entry.view.v},
                     {"weight", entry.weight},
                     {"dx", entry.shift.dx},
                     {"dy", entry.shift.dy}});
  }
  return {{"centre_view", {{"mean_abs_error_rms", comparison.centre_rms}, {"psnr_db", comparison.centre_psnr_db}}},
          {"registration",
           {{"min_weight", TruthComparison::kRegisteredWeight},
            {"depth_edge_margin_px", comparison.depth_edge_margin_px},
            {"views_registered", comparison.registration.registered},
            {"worst_shift_px", comparison.registration.worst},
            {"views", views}}}};
}

cv::Mat CentreErrorPicture(const TruthComparison& comparison) {
  return ColourMapped(comparison.centre_error, kErrorPictureTop);
}

cv::Mat RegistrationPicture(const TruthComparison& comparison) {
  cv::Mat cells(comparison.nv, comparison.nu, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  for (const ViewShift& entry : comparison.registration.views)
    if (entry.registered)
      cells.at<float>(entry.view.v, entry.view.u) =
          static_cast<float>(std::max(std::abs(entry.shift.dx), std::abs(entry.shift.dy)));
  const int cell = std::max(8, 240 / std::max(comparison.nu, comparison.nv));
  return Enlarge(ColourMapped(cells, kRegistrationPictureTop), cell, cell);
}

}  // namespace lfsp::pipeline
