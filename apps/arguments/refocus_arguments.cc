#include "arguments/refocus_arguments.h"

#include <cmath>

#include "lfsp/core/error.h"
#include "stages/refocus_stage.h"

namespace lfsp::cli {

void AddRefocusArguments(CLI::App* command, RefocusArguments& arguments) {
  command
      ->add_option("--interpolation", arguments.interpolation,
                   "Sub-pixel interpolation for refocusing and shearing: linear or cubic (default: linear)")
      ->check(CLI::IsMember({"linear", "cubic"}));
  command->add_flag("--no-weights", arguments.no_weights,
                    "Ignore the input's per-ray weights (default: rays are weighted by them when present)");
}

edit::RefocusOptions ToRefocusOptions(const RefocusArguments& arguments) {
  edit::RefocusOptions options;
  options.interpolation = stages::InterpolationFromName(arguments.interpolation);
  options.use_ray_weights = !arguments.no_weights;
  return options;
}

void RequireRefocusDisparity(float disparity, const std::string& option) {
  constexpr float kMaxDisparity = 1000.0f;
  if (!std::isfinite(disparity) || std::abs(disparity) > kMaxDisparity)
    throw Error(option + ": " + std::to_string(disparity) + " is not a disparity in -" +
                std::to_string(static_cast<int>(kMaxDisparity)) + ".." +
                std::to_string(static_cast<int>(kMaxDisparity)) + " px per view step");
}

}  // namespace lfsp::cli
