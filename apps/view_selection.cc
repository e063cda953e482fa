#include "view_selection.h"

#include <spdlog/spdlog.h>

#include "lfsp/core/view_crop.h"

namespace lfsp::cli {

void AddViewsOption(CLI::App* command, int& views) {
  command
      ->add_option("--views", views,
                   "Process the central N x N views; 0 = the largest central square whose views all have a mean "
                   "weight of at least 0.4 (a lenslet decode's well-lit views: Illum 9x9, F01 7x7; all views "
                   "without weights)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

nlohmann::json SelectViews(Bundle& bundle, int requested, const std::string& source) {
  return ViewChoiceSummary(KeepChosenViews(bundle.light_field, bundle.labels, requested), source);
}

nlohmann::json ViewChoiceSummary(const ViewChoice& choice, const std::string& source) {
  spdlog::info("{}: views: {}", source, choice.reason);
  return {
      {"n", choice.n}, {"of", choice.available}, {"least_mean_weight", choice.least_weight}, {"reason", choice.reason}};
}

}  // namespace lfsp::cli
