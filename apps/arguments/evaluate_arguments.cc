#include "arguments/evaluate_arguments.h"

#include "arguments/refocus_arguments.h"
#include "lfsp/core/error.h"

namespace lfsp::cli {

void AddSegmentationEvaluationArguments(CLI::App* command, SegmentationEvaluationArguments& arguments) {
  command->add_flag("--baselines", arguments.baselines,
                    "Also run and score per-view SLIC and LSC and SLIC supervoxels (row-first, column-first) at the "
                    "same size; default: off");
  command->add_flag("--no-refocus", arguments.no_refocus,
                    "Skip the refocus sweep (LFSP re-run on the light field refocused to each level); default: off");
  command->add_option("--refocus-levels", arguments.refocus_levels, "Refocus levels (disparity shifts, px)")
      ->capture_default_str()
      ->delimiter(',');
  command->add_option("--tolerance", arguments.tolerance, "Boundary-recall tolerance, pixels (chessboard)")
      ->capture_default_str()
      ->check(CLI::Range(0, 100));
}

segment::EvaluationOptions ToEvaluationOptions(const SegmentationEvaluationArguments& arguments) {
  segment::EvaluationOptions evaluation;
  evaluation.boundary_tolerance = arguments.tolerance;
  evaluation.baselines = arguments.baselines;
  evaluation.refocus = !arguments.no_refocus;
  for (const double level : arguments.refocus_levels)
    RequireRefocusDisparity(static_cast<float>(level), OptionName("refocus_levels"));
  evaluation.refocus_levels = arguments.refocus_levels;
  return evaluation;
}

void AddDepthMetricArguments(CLI::App* command, depth::MetricOptions& metrics) {
  command->add_option("--boundary", metrics.boundary, "Ignored frame in pixels (HCI toolkit: 15)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--jump", metrics.discontinuity_jump,
                   "GT disparity step between 4-neighbours that counts as a discontinuity (px/view)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--near", metrics.discontinuity_radius,
                   "Radius (px) around GT discontinuities for the near-discontinuity metrics")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

}  // namespace lfsp::cli
