// `lfsp evaluate`: the parent of every evaluation against ground truth. The kinds themselves register through
// evaluate_registry.h from their own files (evaluate_depth_command.cc, the segment stage's file, ...).

#include <algorithm>

#include "command_registry.h"
#include "evaluate_registry.h"

namespace lfsp::cli {
namespace {

std::vector<EvaluateEntry>& EvaluateRegistry() {
  static std::vector<EvaluateEntry> registry;  // function-local: safe during static initialisation
  return registry;
}

void AddEvaluateCommand(CLI::App& parent) {
  CLI::App* evaluate = parent.add_subcommand("evaluate", "Score a result against ground truth (HCI-style metrics)");
  evaluate->require_subcommand(1);
  for (const EvaluateEntry& entry : RegisteredEvaluateSubcommands()) entry.add(*evaluate);
}

}  // namespace

int RegisterEvaluateSubcommand(EvaluateEntry entry) {
  EvaluateRegistry().push_back(std::move(entry));
  return static_cast<int>(EvaluateRegistry().size());
}

std::vector<EvaluateEntry> RegisteredEvaluateSubcommands() {
  std::vector<EvaluateEntry> sorted = EvaluateRegistry();
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const EvaluateEntry& a, const EvaluateEntry& b) { return a.order < b.order; });
  return sorted;
}

LFSP_REGISTER_COMMAND(90, "evaluate", AddEvaluateCommand);

}  // namespace lfsp::cli
