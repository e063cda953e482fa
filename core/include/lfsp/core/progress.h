#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
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

  // Also reports every Tick to `observer` (label, steps done, total), on the thread that ticks; empty = none. The
  // Python module passes a user's progress callback through this.
  using Observer = std::function<void(const std::string& label, std::size_t done, std::size_t total)>;
  static void SetObserver(Observer observer);

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

// Long work can be stopped from outside (the Python module's Ctrl-C): after RequestCancellation(), the next
// Progress::Tick() of any loop throws Cancelled. Ticks happen between the steps of a stage, outside parallel
// regions, so the exception unwinds through ordinary code and every resource is released on the way out.
class Cancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "cancelled"; }
};
void RequestCancellation();  // async-signal-safe: sets one lock-free atomic flag
void ClearCancellation();
bool CancellationRequested();

}  // namespace lfsp
