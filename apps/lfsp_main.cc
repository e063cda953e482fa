// The `lfsp` command: `lfsp <command> [options]`, COLMAP style. Each command is a thin layer over a library call and
// lives in commands/<name>_command.cc. Bad input (lfsp::Error, usage errors) prints one line and exits 2; anything
// else is an internal failure and exits 1.

#include <spdlog/spdlog.h>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <new>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/version.h"

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

// Library messages name options by their API name ("views_pattern"); on the command line that is --views-pattern.
std::string CommandLineOptionName(const std::string& api_name) {
  std::string flag = "--" + api_name;
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

// Every stage allocates and frees buffers of hundreds of megabytes (views, cost volumes, labels). glibc serves
// blocks above 32 MiB with their own mappings and unmaps them on free, so the kernel faults in and zeroes every page
// again for the next stage: a full Illum `lfsp pipeline` took 1.68 million page faults. Kept in the heap (and the heap
// trimmed only above 1 GiB of free space at its top) the freed memory is reused: 0.66-0.88 million faults, 18 -> 15 s
// wall on the 2-core machine of BENCHMARKS.md, for a peak of 2.69 instead of 2.31 GB. Only the executable does this;
// the Python module leaves its host's allocator alone.
void KeepLargeBuffersInTheHeap() {
#ifdef __GLIBC__
  constexpr int kOneGiB = 1 << 30;
  mallopt(M_MMAP_THRESHOLD, kOneGiB);
  mallopt(M_TRIM_THRESHOLD, kOneGiB);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  KeepLargeBuffersInTheHeap();
  lfsp::SetOptionNamer(CommandLineOptionName);
  CLI::App app{"lfsp: light-field superpixels for lenslet (Lytro) cameras: decode, depth, segmentation, editing",
               "lfsp"};
  app.set_version_flag("--version", std::string("lfsp ") + lfsp::Version());
  app.require_subcommand(1);
  app.fallthrough();
  bool verbose = false;
  bool quiet = false;
  double max_memory_gib = 0.0;
  app.add_flag("-v,--verbose", verbose, "Log details of each step (debug level)");
  app.add_flag("-q,--quiet", quiet, "Only print errors; no progress display");
  app.add_option("--max-memory", max_memory_gib,
                 "Trust sizes declared in input files up to GIB gibibytes of samples (default: at most 16 GiB, and "
                 "no more than 64 MiB + 512x the file's own size)")
      ->check(CLI::Range(0.001, 1.0e6));
  app.add_option("--views-pattern", lfsp::cli::GlobalLoadOptions().views_pattern,
                 "How the files of a views folder are named, e.g. '{row}_{col}.png' or 'view_{row}_{col}.png' "
                 "({index} matches a number that is ignored; the smallest row and column become view 0). Default: "
                 "detected (HCI input_Cam###, <row>_<col>, LFToolbox <name>_<index>_<a>_<b>)");
  app.parse_complete_callback([&] {
    spdlog::set_pattern("lfsp: %v");
    spdlog::set_level(quiet ? spdlog::level::err : verbose ? spdlog::level::debug : spdlog::level::info);
    if (quiet) lfsp::Progress::SetEnabled(false);
    if (max_memory_gib > 0.0)
      lfsp::SetMemoryLimit(static_cast<std::uint64_t>(max_memory_gib * static_cast<double>(1ull << 30)));
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
  } catch (const std::bad_alloc&) {
    // Declared sizes are checked before allocating; what still runs out of memory is an input too large for this
    // machine, which is the user's to change, not a fault of lfsp.
    PrintError("out of memory: the input (or the options asked for) needs more memory than this machine has");
    return kExitBadInput;
  } catch (const std::exception& error) {
    PrintError(std::string("internal failure: ") + error.what());
    return kExitInternal;
  }
  return 0;
}
