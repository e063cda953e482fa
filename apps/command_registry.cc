#include "command_registry.h"

#include <algorithm>

namespace lfsp::cli {
namespace {
std::vector<CommandEntry>& Registry() {
  static std::vector<CommandEntry> registry;  // function-local: safe during static initialisation
  return registry;
}
}  // namespace

int RegisterCommand(CommandEntry entry) {
  Registry().push_back(std::move(entry));
  return static_cast<int>(Registry().size());
}

std::vector<CommandEntry> RegisteredCommands() {
  std::vector<CommandEntry> sorted = Registry();
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const CommandEntry& a, const CommandEntry& b) { return a.order < b.order; });
  return sorted;
}

}  // namespace lfsp::cli
