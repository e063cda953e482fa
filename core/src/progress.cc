#include "lfsp/core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace lfsp {
namespace {
int g_enabled_override = -1;  // -1: decide by terminal, 0: off, 1: on
Progress::Observer g_observer;
std::atomic<bool> g_cancellation_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "RequestCancellation must be async-signal-safe");
}  // namespace

void Progress::SetEnabled(bool enabled) { g_enabled_override = enabled ? 1 : 0; }

void Progress::SetObserver(Observer observer) { g_observer = std::move(observer); }

void RequestCancellation() { g_cancellation_requested.store(true); }
void ClearCancellation() { g_cancellation_requested.store(false); }
bool CancellationRequested() { return g_cancellation_requested.load(); }

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(total),
      start_(std::chrono::steady_clock::now()),
      active_(g_enabled_override == -1 ? isatty(fileno(stderr)) != 0 : g_enabled_override == 1) {}

Progress::~Progress() { Finish(); }

void Progress::Tick(std::size_t steps) {
  if (CancellationRequested()) throw Cancelled();
  const std::size_t done = done_.fetch_add(steps) + steps;
  if (g_observer) g_observer(label_, done, total_);
  if (!active_) return;
  const long long now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
  long long last = last_draw_ns_.load();
  if (now - last < 100'000'000 && done < total_) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now)) return;  // another thread is drawing
  Draw(done);
}

void Progress::Draw(std::size_t done) {
  const double fraction = total_ == 0 ? 1.0 : static_cast<double>(done) / static_cast<double>(total_);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth);
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %zu/%zu %.1fs", label_.c_str(), filled, "##############################",
               kWidth - filled, "", static_cast<int>(fraction * 100.0), done, total_, seconds);
  std::fflush(stderr);
}

void Progress::Finish() {
  if (finished_) return;
  finished_ = true;
  if (!active_) return;
  Draw(done_.load());
  std::fputc('\n', stderr);
}

}  // namespace lfsp
