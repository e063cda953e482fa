#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>

namespace lfsp {

// A one-line progress display on stderr for long loops. It draws only when stderr is a terminal and logging is
// not quiet, so pipes, CI logs and tests stay clean. Tick() is thread-safe and cheap (redraws at most 10x a second).
class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void Tick(std::size_t steps = 1);
  void Finish();

  static void SetEnabled(bool enabled);  // overrides the terminal check (the CLI's -q turns it off)

 private:
  void Draw(std::size_t done);
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<long long> last_draw_ns_{0};
  std::chrono::steady_clock::time_point start_;
  bool active_;
  bool finished_ = false;
};

}  // namespace lfsp
