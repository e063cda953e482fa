#pragma once

#include <chrono>

namespace lfsp {

// Wall time since construction (or the last Lap), and the process's CPU time over the same span: with both, a
// timing shows how well a step used the cores. Every stage and command times its steps with this one clock.
class Stopwatch {
 public:
  Stopwatch();

  double Seconds() const;     // wall seconds since construction or the last Lap
  double CpuSeconds() const;  // CPU seconds of the whole process (all threads) over the same span

  // Wall seconds since construction or the last Lap, and restarts; `cpu_seconds`, when given, receives the CPU time.
  double Lap(double* cpu_seconds = nullptr);

 private:
  std::chrono::steady_clock::time_point start_;
  double cpu_start_;
};

// CPU time of the whole process (all threads) so far, seconds.
double ProcessCpuSeconds();

}  // namespace lfsp
