// `lfsp_bench [--filter TEXT] [--repetitions N]`: runs every registered case in its own child process (so each
// case's peak memory is its own), times `run` several times and prints one Markdown table: median wall time, peak
// RSS, the stage's quality figure, the target, and the ratio to the named baseline case of the same run.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>

#include "bench_case.h"
#include "lfsp/core/stopwatch.h"

namespace {

using lfsp::bench::BenchCase;

struct CaseResult {
  bool ok = false;
  bool skipped = false;
  std::string message;  // quality figure, or the failure / skip reason
  std::vector<double> seconds;
  double peak_mb = 0.0;
  double Median() const {
    if (seconds.empty()) return 0.0;
    std::vector<double> sorted = seconds;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  }
};

// Child side: prepare, run N times, report "ok <quality>\n<t1> <t2> ...\n" or "fail <why>" on the pipe.
[[noreturn]] void RunChild(const BenchCase& bench_case, int repetitions, int fd) {
  std::string report;
  try {
    if (bench_case.prepare) bench_case.prepare();
    std::string quality;
    std::string times;
    for (int i = 0; i < repetitions; ++i) {
      const lfsp::Stopwatch stopwatch;
      quality = bench_case.run();
      const double seconds = stopwatch.Seconds();
      times += std::to_string(seconds) + " ";
    }
    if (bench_case.score) quality += (quality.empty() ? "" : " ") + bench_case.score();
    for (char& c : quality)
      if (c == '\n') c = ' ';
    report = "ok " + quality + "\n" + times + "\n";
  } catch (const std::exception& error) {
    report = std::string("fail ") + error.what() + "\n";
  }
  const ssize_t written = write(fd, report.data(), report.size());
  (void)written;
  close(fd);
  std::_Exit(0);
}

CaseResult RunCase(const BenchCase& bench_case, int repetitions) {
  CaseResult result;
  int fds[2];
  if (pipe(fds) != 0) {
    result.message = "pipe failed";
    return result;
  }
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    RunChild(bench_case, repetitions, fds[1]);
  }
  close(fds[1]);
  std::string report;
  char buffer[4096];
  ssize_t got;
  while ((got = read(fds[0], buffer, sizeof buffer)) > 0) report.append(buffer, static_cast<std::size_t>(got));
  close(fds[0]);
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  result.peak_mb = static_cast<double>(usage.ru_maxrss) / 1024.0;
  if (report.rfind("ok ", 0) != 0) {
    result.message =
        report.empty() ? "crashed (status " + std::to_string(status) + ")" : report.substr(0, report.find('\n'));
    return result;
  }
  const std::size_t newline = report.find('\n');
  result.message = report.substr(3, newline - 3);
  std::string times = report.substr(newline + 1);
  char* cursor = times.data();
  while (true) {
    char* end = nullptr;
    const double value = std::strtod(cursor, &end);
    if (end == cursor) break;
    result.seconds.push_back(value);
    cursor = end;
  }
  result.ok = true;
  return result;
}

std::string CpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace

int main(int argc, char** argv) {
  std::string filter;
  int repetitions_override = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument == "--filter" && i + 1 < argc) {
      filter = argv[++i];
    } else if (argument == "--repetitions" && i + 1 < argc) {
      repetitions_override = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: lfsp_bench [--filter TEXT] [--repetitions N]\n");
      return 2;
    }
  }
  spdlog::set_level(spdlog::level::warn);  // the stages' progress logs would break the table
  const std::string shared = lfsp::bench::SharedDataDir();
  std::printf("Machine: %u cores, %s. Median wall time over the runs shown; peak = max RSS of the case's process.\n\n",
              std::thread::hardware_concurrency(), CpuModel().c_str());
  std::printf("| stage | case | input | median s | runs | peak MB | quality | target | vs baseline |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::map<std::string, double> medians;
  int failures = 0;
  for (const BenchCase& bench_case : lfsp::bench::AllBenchCases()) {
    const std::string full_name = bench_case.stage + "/" + bench_case.name;
    if (!filter.empty() && full_name.find(filter) == std::string::npos) continue;
    CaseResult result;
    const std::string unavailable = bench_case.unavailable ? bench_case.unavailable() : "";
    if (bench_case.needs_shared_data && shared.empty()) {
      result.skipped = true;
      result.message = "skipped: ../shared/data not found";
    } else if (!unavailable.empty()) {
      result.skipped = true;
      result.message = "skipped: " + unavailable;
    } else {
      try {
        if (bench_case.setup) bench_case.setup();
        result = RunCase(bench_case, repetitions_override > 0 ? repetitions_override : bench_case.repetitions);
      } catch (const std::exception& error) {
        result.message = std::string("setup failed: ") + error.what();
      }
    }
    std::string ratio = "";
    if (result.ok) {
      medians[bench_case.name] = result.Median();
      const auto baseline = medians.find(bench_case.baseline);
      if (!bench_case.baseline.empty() && baseline != medians.end() && baseline->second > 0.0) {
        const double scale = bench_case.baseline_scale;
        char scaled[32] = "";
        if (scale != 1.0) std::snprintf(scaled, sizeof scaled, "%g x ", scale);
        char text[160];
        std::snprintf(text, sizeof text, "x%.2f of %s%s", result.Median() / (scale * baseline->second), scaled,
                      bench_case.baseline.c_str());
        ratio = text;
      }
    } else if (!result.skipped) {
      ++failures;
    }
    char median[32] = "-";
    char peak[32] = "-";
    if (result.ok) {
      std::snprintf(median, sizeof median, "%.3f", result.Median());
      std::snprintf(peak, sizeof peak, "%.0f", result.peak_mb);
    }
    std::printf("| %s | %s | %s | %s | %zu | %s | %s | %s | %s |\n", bench_case.stage.c_str(), bench_case.name.c_str(),
                bench_case.input.c_str(), median, result.seconds.size(), peak,
                result.ok ? result.message.c_str() : ("**" + result.message + "**").c_str(), bench_case.target.c_str(),
                ratio.c_str());
    std::fflush(stdout);
  }
  return failures == 0 ? 0 : 1;
}
