#include "input_loading.h"

namespace lfsp::cli {

LoadOptions& GlobalLoadOptions() {
  static LoadOptions options;
  return options;
}

Bundle LoadInput(const std::filesystem::path& path) { return LoadLightField(path, GlobalLoadOptions()); }

}  // namespace lfsp::cli
