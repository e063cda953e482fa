#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lfsp::bench {

// One row of the `make bench` table. `prepare` runs once, untimed (load inputs, make synthetic data); `run` is
// timed, several times, and returns the stage's quality figure as text (e.g. "BadPix0.07=12.3%", or "" if none).
// Each case runs in its own child process so its peak memory (max RSS) is measured on its own.
// `baseline` names another case whose median is printed as a ratio next to this one ("x0.35 of <baseline>").
struct BenchCase {
  std::string stage;
  std::string name;
  std::string input;   // e.g. "antinous 9x9x512x512"
  std::string target;  // the target, e.g. "<= 0.5 s", for the table
  std::function<void()> prepare;
  // Runs in the bench's own process before the case's process starts, so neither its time nor its memory counts:
  // for inputs made by another command (a full-size simulated capture) that would otherwise set the case's peak.
  std::function<void()> setup;
  std::function<std::string()> run;
  // Optional, untimed: runs once after the timed repetitions and its text follows run's in the quality column, so
  // that scoring a result (which can cost as much as making it) does not count in the stage's time.
  std::function<std::string()> score;
  std::string baseline;
  // The ratio is printed against baseline_scale x the baseline's median: 2 for two jobs against one run twice.
  double baseline_scale = 1.0;
  int repetitions = 5;
  bool needs_shared_data = false;
  // Optional: why the case cannot run here ("" when it can), e.g. no reference build; it is then listed as skipped.
  std::function<std::string()> unavailable;
};

// Called at static-initialisation time by LFSP_BENCH_CASE in each bench/<stage>_bench.cc.
int RegisterBenchCase(std::function<BenchCase()> make);
std::vector<BenchCase> AllBenchCases();

// ../shared/data, or "" if absent (cases that need it are then listed as skipped).
std::string SharedDataDir();

// Runs `lfsp -q <arguments>` (the executable of this build) with `environment` ("NAME=value ...", shell syntax)
// before it, its output discarded; throws if it fails.
void RunLfsp(const std::string& arguments, const std::string& environment = "");

// The same with another `lfsp` executable, e.g. the reference build (ReferenceLfsp).
void RunLfspBinary(const std::string& binary, const std::string& arguments, const std::string& environment = "");

// The reference build's `lfsp` (issue 46: ratios against today's binary in the same run): $LFSP_BENCH_REFERENCE,
// else the one `make reference` builds (LFSP_REFERENCE_BINARY); "" when neither exists.
std::string ReferenceLfsp();

// A JSON file (a run's summary.json), parsed; throws if it is not JSON.
nlohmann::json ReadJson(const std::filesystem::path& path);

// `value` with `decimals` digits after the point, for the quality column.
std::string Fixed(double value, int decimals);

// The quality figures of a `lfsp pipeline` run folder, from its summary.json (apps_bench.cc).
std::string PipelineFigures(const std::filesystem::path& out);

// The full-size simulated capture (.LFR for "illum", .lfp for "f01") of a built-in scene, with its white images and
// ground truth, made once in the temporary folder and reused by every case and later runs.
std::filesystem::path FullSizeCapture(const std::string& camera, const std::string& scene);

}  // namespace lfsp::bench

#define LFSP_BENCH_CONCAT_INNER(a, b) a##b
#define LFSP_BENCH_CONCAT(a, b) LFSP_BENCH_CONCAT_INNER(a, b)
// Usage: LFSP_BENCH_CASE { BenchCase c; ...; return c; }
#define LFSP_BENCH_CASE                                                                 \
  static ::lfsp::bench::BenchCase LFSP_BENCH_CONCAT(lfsp_bench_make_, __LINE__)();      \
  [[maybe_unused]] static const int LFSP_BENCH_CONCAT(lfsp_bench_reg_, __LINE__) =      \
      ::lfsp::bench::RegisterBenchCase(&LFSP_BENCH_CONCAT(lfsp_bench_make_, __LINE__)); \
  static ::lfsp::bench::BenchCase LFSP_BENCH_CONCAT(lfsp_bench_make_, __LINE__)()
