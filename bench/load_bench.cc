// Threads under load (issue 48): each stage through the `lfsp` executable, idle, as two jobs started together, and
// beside one and two busy threads, on the 2-core machine. The loaded rows print their ratio to the idle row of the
// same run (two jobs: to twice the idle time). The fair share beside k busy threads is (2 + k) / 2 of the idle time
// for a job whose two threads are always busy: two cores shared by 2 + k runnable threads. A row with libgomp's own
// spinning wait (GOMP_SPINCOUNT=300000, what it does when OMP_WAIT_POLICY is unset) shows what the passive default
// costs on an idle machine.

#include <atomic>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench_case.h"

namespace lfsp::bench {
namespace {

namespace fs = std::filesystem;

fs::path Antinous() { return fs::path(SharedDataDir()) / "hci" / "antinous"; }
fs::path AntinousBundle() { return fs::temp_directory_path() / "lfsp_bench_load_antinous.h5"; }

// One job: a command line of `lfsp` with {out} standing for its own output path (two jobs at once write apart).
struct Job {
  std::string name;
  std::string input;
  std::string arguments;
  std::function<void()> setup;
  bool needs_shared_data = false;  // antinous comes from ../shared/data; the Illum capture is simulated
};

std::vector<Job> Jobs() {
  const auto antinous_bundle = [] {
    if (!fs::exists(AntinousBundle())) RunLfsp("convert " + Antinous().string() + " " + AntinousBundle().string());
  };
  const auto illum_capture = [] { FullSizeCapture("illum", "two-horses"); };
  const std::string capture = (fs::temp_directory_path() / "lfsp_bench_two_horses_illum" / "capture.LFR").string();
  const std::string bundle = AntinousBundle().string();
  const std::string disparity = (Antinous() / "gt_disp_lowres.pfm").string();
  return {
      {"decode-illum", "Illum 7728x5368 two-horses capture", "decode " + capture + " --out {out}.h5", illum_capture},
      {"depth-antinous", "antinous 9x9x512x512 (.h5)", "depth " + bundle + " --out {out}.pfm", antinous_bundle, true},
      {"segment-antinous", "antinous 9x9x512x512 (.h5), ground-truth disparity",
       "segment " + bundle + " --disparity " + disparity + " --out {out}.h5", antinous_bundle, true},
      {"refocus-antinous", "antinous 9x9x512x512 (.h5): 16-slice stack + all-in-focus",
       "refocus " + bundle + " --stack 16 --all-in-focus --disparity " + disparity + " --out {out}", antinous_bundle,
       true},
      {"pipeline-illum", "Illum 7728x5368 two-horses capture", "pipeline " + capture + " --out {out}", illum_capture},
  };
}

std::string Substituted(std::string arguments, const fs::path& out) {
  const std::string key = "{out}";
  for (std::size_t at; (at = arguments.find(key)) != std::string::npos;) arguments.replace(at, key.size(), out);
  return arguments;
}

fs::path OutputOf(const std::string& case_name, int copy) {
  return fs::temp_directory_path() / ("lfsp_bench_load_" + case_name + "_" + std::to_string(copy));
}

// Threads that only compute, as a busy neighbour does (a build, a numerical program). They run until the case's
// process ends.
void StartBusyThreads(int count) {
  static std::atomic<bool> stop{false};
  for (int i = 0; i < count; ++i)
    std::thread([] {
      volatile double sink = 1.0;
      while (!stop.load(std::memory_order_relaxed)) sink = sink * 1.0000001 + 1e-9;
    }).detach();
}

enum class Load { kIdleSpinning, kIdle, kTwoAtOnce, kOneBusyThread, kTwoBusyThreads };

BenchCase LoadCase(const Job& job, Load load) {
  static const char* const kSuffix[] = {"-idle-spinning", "-idle", "-two-at-once", "-beside-1-busy", "-beside-2-busy"};
  BenchCase c;
  c.stage = "load";
  c.name = job.name + kSuffix[static_cast<int>(load)];
  c.input = job.input;
  c.needs_shared_data = job.needs_shared_data;
  c.repetitions = 3;
  c.setup = job.setup;
  const std::string idle = job.name + kSuffix[static_cast<int>(Load::kIdle)];
  switch (load) {
    case Load::kIdleSpinning:
      c.target = "libgomp's spinning wait: the idle row should be no slower than this";
      break;
    case Load::kIdle:
      c.baseline = job.name + kSuffix[static_cast<int>(Load::kIdleSpinning)];
      c.target = "no slower than spinning, within noise";
      break;
    case Load::kTwoAtOnce:
      c.baseline = idle;
      c.baseline_scale = 2.0;
      c.target = "<= 1.1 x two idle runs";
      break;
    case Load::kOneBusyThread:
      c.baseline = idle;
      c.target = "<= 1.73 x idle (fair 1.5 x, + 15 %)";
      c.prepare = [] { StartBusyThreads(1); };
      break;
    case Load::kTwoBusyThreads:
      c.baseline = idle;
      c.target = "<= 2.3 x idle (fair 2 x, + 15 %)";
      c.prepare = [] { StartBusyThreads(2); };
      break;
  }
  c.run = [job, load, name = c.name] {
    const int copies = load == Load::kTwoAtOnce ? 2 : 1;
    const std::string environment = load == Load::kIdleSpinning ? "GOMP_SPINCOUNT=300000 " : "";
    std::vector<std::thread> running;
    std::vector<std::exception_ptr> failures(copies);
    for (int copy = 0; copy < copies; ++copy)
      running.emplace_back([&, copy] {
        try {
          for (const char* extension : {"", ".h5", ".pfm"}) fs::remove_all(OutputOf(name, copy) += extension);
          RunLfsp(Substituted(job.arguments, OutputOf(name, copy)), environment);
        } catch (...) {
          failures[copy] = std::current_exception();
        }
      });
    for (std::thread& thread : running) thread.join();
    for (const std::exception_ptr& failure : failures)
      if (failure) std::rethrow_exception(failure);
    return std::string();
  };
  return c;
}

constexpr Load kLoads[] = {Load::kIdleSpinning, Load::kIdle, Load::kTwoAtOnce, Load::kOneBusyThread,
                           Load::kTwoBusyThreads};

// One case per job and load, a job's rows together in the table.
[[maybe_unused]] const int kRegistered = [] {
  const std::size_t jobs = Jobs().size();
  for (std::size_t j = 0; j < jobs; ++j)
    for (Load load : kLoads) RegisterBenchCase([j, load] { return LoadCase(Jobs()[j], load); });
  return 0;
}();

}  // namespace
}  // namespace lfsp::bench
