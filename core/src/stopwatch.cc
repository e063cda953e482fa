#include "lfsp/core/stopwatch.h"

#include <ctime>

namespace lfsp {

double ProcessCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

Stopwatch::Stopwatch() : start_(std::chrono::steady_clock::now()), cpu_start_(ProcessCpuSeconds()) {}

double Stopwatch::Seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double Stopwatch::CpuSeconds() const { return ProcessCpuSeconds() - cpu_start_; }

double Stopwatch::Lap(double* cpu_seconds) {
  const auto now = std::chrono::steady_clock::now();
  const double cpu = ProcessCpuSeconds();
  const double seconds = std::chrono::duration<double>(now - start_).count();
  if (cpu_seconds != nullptr) *cpu_seconds = cpu - cpu_start_;
  start_ = now;
  cpu_start_ = cpu;
  return seconds;
}

}  // namespace lfsp
