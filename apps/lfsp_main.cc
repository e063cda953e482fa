// The `lfsp` command: `lfsp <command> [options]`, COLMAP style. Each command is a thin layer over a library call and
// lives in commands/<name>_command.cc. Bad input (lfsp::Error, usage errors) prints one line and exits 2; anything
// else is an internal failure and exits 1.

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/core/progress.h"

namespace {

constexpr int kExitBadInput = 2;
constexpr int kExitInternal = 1;

void PrintError(const std::string& message) {
  // One line, whatever the message holds.
  std::string line = message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "lfsp: error: %s\n", line.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lfsp: light-field superpixels for lenslet (Lytro) cameras: decode, depth, segmentation, editing",
               "lfsp"};
  app.set_version_flag("--version", std::string("lfsp ") + LFSP_VERSION);
  app.require_subcommand(1);
  app.fallthrough();
  bool verbose = false;
  bool quiet = false;
  app.add_flag("-v,--verbose", verbose, "Log details of each step (debug level)");
  app.add_flag("-q,--quiet", quiet, "Only print errors; no progress display");
  app.parse_complete_callback([&] {
    spdlog::set_pattern("lfsp: %v");
    spdlog::set_level(quiet ? spdlog::level::err : verbose ? spdlog::level::debug : spdlog::level::info);
    if (quiet) lfsp::Progress::SetEnabled(false);
  });
  for (const auto& command : lfsp::cli::RegisteredCommands()) command.add(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForAllHelp& help) {
    return app.exit(help);
  } catch (const CLI::CallForVersion& version) {
    return app.exit(version);
  } catch (const CLI::ParseError& error) {
    PrintError(std::string(error.what()) + " (see lfsp --help)");
    return kExitBadInput;
  } catch (const lfsp::Error& error) {
    PrintError(error.what());
    return kExitBadInput;
  } catch (const std::exception& error) {
    PrintError(std::string("internal failure: ") + error.what());
    return kExitInternal;
  }
  return 0;
}
