#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace lfsp::cli {

// `lfsp evaluate <kind>`: each kind (depth, segmentation, ...) lives in its own apps/commands/evaluate_<kind>*.cc
// and registers itself here, so adding one touches no shared file. The `evaluate` parent (evaluate_command.cc)
// adds every registered kind, in `order`, when the command line is built (after static initialisation).
struct EvaluateEntry {
  int order;
  std::string name;
  std::function<void(CLI::App& evaluate)> add;  // adds the `evaluate <name>` subcommand and its callback
};

int RegisterEvaluateSubcommand(EvaluateEntry entry);
std::vector<EvaluateEntry> RegisteredEvaluateSubcommands();  // sorted by order

}  // namespace lfsp::cli

#define LFSP_EVALUATE_CONCAT_INNER(a, b) a##b
#define LFSP_EVALUATE_CONCAT(a, b) LFSP_EVALUATE_CONCAT_INNER(a, b)
// Usage at namespace scope: LFSP_REGISTER_EVALUATE_SUBCOMMAND(20, "segmentation", AddEvaluateSegmentation);
// (depth uses order 10).
#define LFSP_REGISTER_EVALUATE_SUBCOMMAND(order, name, add_function)                      \
  [[maybe_unused]] static const int LFSP_EVALUATE_CONCAT(lfsp_evaluate_kind_, __LINE__) = \
      ::lfsp::cli::RegisterEvaluateSubcommand({order, name, add_function})
