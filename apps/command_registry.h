#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace lfsp::cli {

// Each subcommand lives in apps/commands/<name>_command.cc and registers itself with LFSP_REGISTER_COMMAND, so
// adding a command touches no shared file. `order` fixes its place in `lfsp --help` (docs/DESIGN.md order:
// info 10, simulate 20, whites 30, decode 40, calibrate 50, rectify 60, depth 70, segment 80, evaluate 90,
// noise-study 100, refocus 110, recolor 120, pipeline 130, view 140).
struct CommandEntry {
  int order;
  std::string name;
  std::function<void(CLI::App& parent)> add;  // adds the subcommand and its callback to `parent`
};

int RegisterCommand(CommandEntry entry);
std::vector<CommandEntry> RegisteredCommands();  // sorted by order

}  // namespace lfsp::cli

#define LFSP_CLI_CONCAT_INNER(a, b) a##b
#define LFSP_CLI_CONCAT(a, b) LFSP_CLI_CONCAT_INNER(a, b)
// Usage at namespace scope: LFSP_REGISTER_COMMAND(70, "depth", AddDepthCommand);
#define LFSP_REGISTER_COMMAND(order, name, add_function)                       \
  [[maybe_unused]] static const int LFSP_CLI_CONCAT(lfsp_command_, __LINE__) = \
      ::lfsp::cli::RegisterCommand({order, name, add_function})
