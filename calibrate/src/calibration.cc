// The calibration pipeline: input checks, observations, initialisation, and the three Ceres stages.

#include "lfsp/calibrate/calibration.h"

#include <omp.h>

#include <ceres/ceres.h>
#include <spdlog/spdlog.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "initialisation.h"
#include "lfsp/core/error.h"
#include "lfsp/core/stopwatch.h"
#include "ray_distance_cost.h"

namespace lfsp::calibrate {
namespace {

using internal::Observation;
using internal::Pose;

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::string SettingName(const CaptureCorners& c) {
  std::ostringstream s;
  s << "camera " << (c.serial.empty() ? "?" : c.serial) << ", zoom step "
    << (c.zoom_step ? std::to_string(*c.zoom_step) : "?") << ", focus step "
    << (c.focus_step ? std::to_string(*c.focus_step) : "?");
  return s.str();
}

// Every capture must come from one decoded geometry, one board and one camera setting.
void CheckConsistency(const std::vector<CaptureCorners>& captures, const CalibrationOptions& options,
                      std::vector<std::string>& warnings) {
  const CaptureCorners& first = captures.front();
  std::vector<std::string> other_size, other_grid;
  for (const auto& c : captures) {
    const LightFieldShape& a = c.shape;
    const LightFieldShape& b = first.shape;
    if (a.nu != b.nu || a.nv != b.nv || a.width != b.width || a.height != b.height) other_size.push_back(c.name);
    // Partial boards (the visible part of a board larger than the views) differ in size by nature: each capture's
    // corners are indexed from its own first visible corner, and its pose absorbs the offset.
    const bool partial = c.partial_board && first.partial_board;
    if (!partial && (c.corners_x != first.corners_x || c.corners_y != first.corners_y)) other_grid.push_back(c.name);
  }
  if (!other_size.empty()) {
    throw Error("calibration: captures of different light-field sizes: " + Join(other_size) + " differ from " +
                first.name + " (" + ToString(first.shape) + ")");
  }
  if (!other_grid.empty())
    throw Error("calibration: captures searched with different grid sizes: " + Join(other_grid) + " vs " + first.name);

  // Group by camera setting; report each group's captures by name.
  std::map<std::string, std::vector<std::string>> settings;
  for (const auto& c : captures) settings[SettingName(c)].push_back(c.name);
  if (settings.size() > 1) {
    std::string message =
        "calibration: captures from different cameras or zoom/focus steps (the intrinsics change "
        "with them):";
    for (const auto& [setting, names] : settings) message += " [" + setting + ": " + Join(names) + "]";
    if (!options.allow_mixed_settings) throw Error(message + "; calibrate each setting separately");
    warnings.push_back(message);
  }
}

std::vector<Observation> MakeObservations(const std::vector<CaptureCorners>& captures, double square_size) {
  std::vector<Observation> observations;
  const Eigen::Vector4d centre = CentreIndex(captures.front().shape);
  for (std::size_t c = 0; c < captures.size(); ++c) {
    const CaptureCorners& capture = captures[c];
    for (const auto& view : capture.views) {
      for (int b = 0; b < capture.corners_y; ++b) {
        for (int a = 0; a < capture.corners_x; ++a) {
          const cv::Point2d& p = view.corners[static_cast<std::size_t>(b * capture.corners_x + a)];
          observations.push_back({static_cast<int>(c), p.x - centre(0), p.y - centre(1), view.view.u - centre(2),
                                  view.view.v - centre(3), a * square_size, b * square_size});
        }
      }
    }
  }
  return observations;
}

// The residual norm (mm) of every observation for the current parameters.
std::vector<double> ResidualNorms(const std::vector<Observation>& observations, const Slopes& slopes,
                                  const std::array<double, 5>& distortion, const std::vector<Pose>& poses) {
  std::vector<double> norms(observations.size());
#pragma omp parallel for
  for (std::size_t n = 0; n < observations.size(); ++n) {
    const internal::RayDistanceCost cost(observations[n]);
    double r[3];
    cost(slopes.data(), distortion.data(), poses[static_cast<std::size_t>(observations[n].capture)].data(), r);
    norms[n] = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  }
  return norms;
}

double Rms(const std::vector<double>& norms) {
  double sum = 0;
  for (double v : norms) sum += v * v;
  return norms.empty() ? 0 : std::sqrt(sum / static_cast<double>(norms.size()));
}

// An RMS estimate that ignores outliers: the median distance times sqrt(2) / 1.1774 (for a 2-D Gaussian offset
// the median distance is 1.1774 sigma and the RMS distance sqrt(2) sigma).
double RobustRms(std::vector<double> norms) {
  if (norms.empty()) return 0;
  std::nth_element(norms.begin(), norms.begin() + static_cast<std::ptrdiff_t>(norms.size() / 2), norms.end());
  return norms[norms.size() / 2] * std::sqrt(2.0) / 1.1774;
}

struct Parameters {
  Slopes slopes{};
  std::array<double, 5> distortion{};
  std::vector<Pose> poses;
};

// One Ceres stage over the chosen observations. Returns the number of iterations.
int SolveStage(const std::vector<Observation>& observations, const std::vector<std::size_t>& chosen,
               Parameters& parameters, bool with_distortion, double huber_mm, const CalibrationOptions& options) {
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  std::unique_ptr<ceres::LossFunction> loss;
  if (huber_mm > 0) loss = std::make_unique<ceres::HuberLoss>(huber_mm);
  for (std::size_t n : chosen) {
    const Observation& o = observations[n];
    problem.AddResidualBlock(internal::RayDistanceCost::Create(o), loss.get(), parameters.slopes.data(),
                             parameters.distortion.data(),
                             parameters.poses[static_cast<std::size_t>(o.capture)].data());
  }
  // Gauge: H11 and H22 stay at zero (calibration.h).
  problem.SetManifold(parameters.slopes.data(), new ceres::SubsetManifold(8, {0, 4}));
  if (!with_distortion) problem.SetParameterBlockConstant(parameters.distortion.data());

  ceres::Solver::Options solver;
  // Poses are eliminated first (each touches only its own observations); the reduced system is 13 x 13.
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (auto& pose : parameters.poses)
    if (problem.HasParameterBlock(pose.data())) ordering->AddElementToGroup(pose.data(), 0);
  ordering->AddElementToGroup(parameters.slopes.data(), 1);
  ordering->AddElementToGroup(parameters.distortion.data(), 1);
  solver.linear_solver_ordering = ordering;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = 1e-10;
  solver.parameter_tolerance = 1e-10;
  solver.gradient_tolerance = 1e-12;
  solver.num_threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) throw Error("calibration: the solver failed: " + summary.message);
  spdlog::debug(
      "solver: {:.2f} s total, preprocessor {:.2f} s, residuals {:.2f} s, jacobians {:.2f} s, linear solver {:.2f} s",
      summary.total_time_in_seconds, summary.preprocessor_time_in_seconds, summary.residual_evaluation_time_in_seconds,
      summary.jacobian_evaluation_time_in_seconds, summary.linear_solver_time_in_seconds);
  return static_cast<int>(summary.iterations.size());
}

}  // namespace

double RayDistance(const RayModel& model, const std::array<double, 3>& rotation,
                   const std::array<double, 3>& translation, double i, double j, double k, double l, double x,
                   double y) {
  const Ray ray = model.PhysicalRay(i, j, k, l);
  const Eigen::Vector3d axis(rotation[0], rotation[1], rotation[2]);
  const double angle = axis.norm();
  const Eigen::Matrix3d r =
      angle > 0 ? Eigen::AngleAxisd(angle, axis / angle).toRotationMatrix() : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d p =
      r * Eigen::Vector3d(x, y, 0) + Eigen::Vector3d(translation[0], translation[1], translation[2]);
  const Eigen::Vector3d w = p - Eigen::Vector3d(ray.s, ray.t, 0), d(ray.u, ray.v, 1);
  return w.cross(d).norm() / d.norm();
}

Calibration Calibrate(const std::vector<CaptureCorners>& all_captures, const CalibrationOptions& options) {
  if (all_captures.empty()) throw Error("calibration: no captures given");
  if (!(options.square_size > 0)) throw Error("calibration: the square size must be positive");
  Calibration result;
  CheckConsistency(all_captures, options, result.warnings);

  // Keep the captures with enough views.
  std::vector<CaptureCorners> captures;
  for (const auto& c : all_captures) {
    if (static_cast<int>(c.views.size()) < options.min_views_per_capture) {
      result.rejected_captures.push_back(c.name + ": the board was tracked in only " + std::to_string(c.views.size()) +
                                         " views (" + std::to_string(c.dark_views.size()) + " dark, " +
                                         std::to_string(c.edge_views.size()) + " at the lenslet's edge, " +
                                         std::to_string(c.failed_views.size()) + " failed), need " +
                                         std::to_string(options.min_views_per_capture));
      result.warnings.push_back("dropped " + result.rejected_captures.back());
    } else {
      captures.push_back(c);
    }
  }
  if (static_cast<int>(captures.size()) < options.min_captures) {
    throw Error("calibration: only " + std::to_string(captures.size()) + " usable capture(s), need at least " +
                std::to_string(options.min_captures) +
                (result.rejected_captures.empty() ? "" : "; rejected: " + Join(result.rejected_captures)));
  }
  if (static_cast<int>(captures.size()) < options.recommended_captures) {
    result.warnings.push_back("only " + std::to_string(captures.size()) + " usable captures; " +
                              std::to_string(options.recommended_captures) +
                              " or more diverse poses are recommended for a reliable calibration");
  }
  for (const auto& w : result.warnings) spdlog::warn("{}", w);

  const CaptureCorners& first = captures.front();
  result.shape = first.shape;
  result.shape.channels = 1;
  result.corners_x = first.corners_x;
  result.corners_y = first.corners_y;
  result.square_size = options.square_size;
  result.camera_model = first.camera_model;
  result.serial = first.serial;
  result.zoom_step = first.zoom_step;
  result.focus_step = first.focus_step;

  const Stopwatch stopwatch;
  const std::vector<Observation> observations = MakeObservations(captures, options.square_size);
  const internal::InitialEstimate initial =
      internal::InitialiseFromHomographies(captures, observations, options.square_size);
  Parameters parameters{initial.slopes, {0, 0, 0, 0, 0}, initial.poses};

  std::vector<std::size_t> all(observations.size()), subset;
  for (std::size_t n = 0; n < observations.size(); ++n) all[n] = n;
  // The first stages use a lattice of views: they only need to get close; the refine stage uses everything.
  const int stride = std::max(1, options.view_stride);
  const Eigen::Vector4d centre = CentreIndex(result.shape);
  for (std::size_t n = 0; n < observations.size(); ++n) {
    const int u = static_cast<int>(std::lround(observations[n].k + centre(2)));
    const int v = static_cast<int>(std::lround(observations[n].l + centre(3)));
    if (u % stride == 0 && v % stride == 0) subset.push_back(n);
  }
  if (subset.size() < all.size() / 8) subset = all;

  const auto report = [&](const std::string& name, const std::vector<std::size_t>& used, int iterations) {
    const auto norms = ResidualNorms(observations, parameters.slopes, parameters.distortion, parameters.poses);
    std::vector<double> chosen;
    for (std::size_t n : used) chosen.push_back(norms[n]);
    result.stages.push_back({name, Rms(chosen), iterations, static_cast<int>(used.size()), stopwatch.Seconds()});
    spdlog::info("calibration stage {}: RMS ray reprojection error {:.4f} mm over {} corners ({} iterations)", name,
                 result.stages.back().rms_mm, used.size(), iterations);
    return norms;
  };
  auto norms = report("initial", all, 0);
  // Huber scales follow the previous stage's outlier-free error, so a few bad corners cannot pull the fit.
  int iterations = SolveStage(observations, subset, parameters, false, 3.0 * RobustRms(norms), options);
  norms = report("no-distortion", subset, iterations);
  iterations = SolveStage(observations, subset, parameters, true, 3.0 * RobustRms(norms), options);
  norms = report("with-distortion", subset, iterations);

  // Refine: every view, outliers dropped, Huber loss at a scale matched to the remaining error.
  const double robust = RobustRms(norms);
  std::vector<std::size_t> inliers;
  for (std::size_t n : all)
    if (norms[n] <= options.outlier_threshold * robust) inliers.push_back(n);
  iterations = SolveStage(observations, inliers, parameters, true, options.huber_scale * robust, options);
  norms = report("refine", inliers, iterations);
  result.rms_mm = result.stages.back().rms_mm;

  result.model.H = IntrinsicsFromSlopes(parameters.slopes, result.shape);
  result.model.distortion = Distortion::FromArray(parameters.distortion);

  // Per-capture figures over the inliers.
  std::vector<double> sum(captures.size(), 0.0);
  std::vector<int> count(captures.size(), 0);
  for (std::size_t n : inliers) {
    const auto c = static_cast<std::size_t>(observations[n].capture);
    sum[c] += norms[n] * norms[n];
    ++count[c];
  }
  for (std::size_t c = 0; c < captures.size(); ++c) {
    CapturePose pose;
    pose.name = captures[c].name;
    const Pose& p = parameters.poses[c];
    pose.rotation = {p[0], p[1], p[2]};
    pose.translation = {p[3], p[4], p[5]};
    pose.rms_mm = count[c] > 0 ? std::sqrt(sum[c] / count[c]) : 0;
    pose.observations = count[c];
    for (const auto& view : captures[c].views) pose.views.push_back(view.view);
    pose.dark_views = captures[c].dark_views;
    pose.edge_views = captures[c].edge_views;
    pose.failed_views = captures[c].failed_views;
    result.captures.push_back(std::move(pose));
  }
  return result;
}

}  // namespace lfsp::calibrate
