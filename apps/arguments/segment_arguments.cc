#include "arguments/segment_arguments.h"

#include <string>

namespace lfsp::cli {
namespace {

// Adds --name for one numeric parameter, documenting its default.
template <typename T>
void AddParameter(CLI::App* command, const std::string& name, T& value, const std::string& help) {
  command->add_option(name, value, help)->capture_default_str();
}

}  // namespace

void AddLfspParameters(CLI::App* command, segment::LfspParams& p) {
  AddParameter(command, "--size", p.size, "Superpixel size: seed grid step in the centre view, pixels");
  AddParameter(command, "--lambda-p", p.lambda_p, "Position weight lambda_p (Table II)");
  AddParameter(command, "--lambda-d", p.lambda_d, "Disparity weight lambda_d (Table II)");
  AddParameter(command, "--lambda-s", p.lambda_s, "Plane smoothness weight lambda_s (Table II)");
  AddParameter(command, "--lambda-b", p.lambda_b, "Boundary weight lambda_b (Table II)");
  AddParameter(command, "--pen-spatial", p.pen_spatial, "Spatial-neighbour penalty E_pen_s (Table II)");
  AddParameter(command, "--pen-mixed", p.pen_mixed, "Mixed-neighbour penalty E_pen_m (Table II)");
  AddParameter(command, "--pen-angular", p.pen_angular, "Angular-neighbour penalty E_pen_a (Table II)");
  AddParameter(command, "--colour-scale", p.colour_scale, "Lab distance worth one unit of energy");
  AddParameter(command, "--slic-iterations", p.slic_iterations, "Iterations of the initial centre-view SLIC");
  AddParameter(
      command, "--iterations", p.iterations,
      "Outer block-coordinate-descent iterations (0 = none: the projection, then the carry of the centre labels)");
  AddParameter(command, "--plane-iterations", p.plane_iterations, "Plane-smoothing rounds per outer iteration");
  AddParameter(command, "--inlier-threshold", p.inlier_threshold,
               "Disparity residual (px) above which a pixel does not pull its plane");
  AddParameter(command, "--hinge-penalty", p.hinge_penalty, "Cost of a hinge boundary (px^2)");
  AddParameter(command, "--occlusion-penalty", p.occlusion_penalty, "Cost of an occlusion boundary (px^2)");
  AddParameter(command, "--impossible-penalty", p.impossible_penalty,
               "Extra cost when an occlusion's claimed front is behind (px^2)");
  AddParameter(command, "--convergence", p.convergence,
               "Stop when fewer than this fraction of rays changed label in an iteration");
  AddParameter(command, "--presmooth", p.presmooth,
               "Gaussian smoothing (px) of the colours compared, against noise; -1 = from the estimated noise "
               "(none on clean views, up to 1.5 px), 0 = off");
  AddParameter(command, "--threads", p.threads, "OpenMP threads (0 = all)");
}

}  // namespace lfsp::cli
