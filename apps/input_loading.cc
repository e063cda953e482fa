#include "input_loading.h"

#include <utility>

#include "view_selection.h"

namespace lfsp::cli {

LoadOptions& GlobalLoadOptions() {
  static LoadOptions options;
  return options;
}

Bundle LoadInput(const std::filesystem::path& path) { return LoadLightField(path, GlobalLoadOptions()); }

Bundle LoadSelectedViews(const std::filesystem::path& path, int requested, nlohmann::json& views_summary) {
  LoadedViews loaded = LoadCentralViews(path, requested, GlobalLoadOptions());
  views_summary = ViewChoiceSummary(loaded.choice, path.string());
  return std::move(loaded.bundle);
}

}  // namespace lfsp::cli
