#include "lfsp/core/foreign_crash_guard.h"

#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstring>
#include <mutex>

namespace lfsp {
namespace {

constexpr int kGuardedSignals[] = {SIGSEGV, SIGBUS, SIGFPE};

// The line to print, made before any crash: a signal handler may only write and exit.
char g_message[1024];
std::size_t g_message_length = 0;
int g_depth = 0;
struct sigaction g_previous[sizeof kGuardedSignals / sizeof kGuardedSignals[0]];
std::mutex g_mutex;

void OnCrash(int) {
  const ssize_t written = write(STDERR_FILENO, g_message, g_message_length);
  (void)written;
  _exit(2);
}

}  // namespace

ForeignCrashGuard::ForeignCrashGuard(const std::string& path, const char* library) {
#ifndef LFSP_FUZZ_BUILD
  const std::lock_guard<std::mutex> lock(g_mutex);
  if (g_depth++ > 0) {
    installed_ = true;
    return;
  }
  std::string line = path + ": malformed file (" + library + " crashed reading it)";
  std::replace(line.begin(), line.end(), '\n', ' ');
  line = "lfsp: error: " + line.substr(0, sizeof g_message - 16) + "\n";
  std::memcpy(g_message, line.data(), line.size());
  g_message_length = line.size();
  struct sigaction action {};
  action.sa_handler = OnCrash;
  sigemptyset(&action.sa_mask);
  for (std::size_t i = 0; i < std::size(kGuardedSignals); ++i) sigaction(kGuardedSignals[i], &action, &g_previous[i]);
  installed_ = true;
#else
  (void)path;
  (void)library;
#endif
}

ForeignCrashGuard::~ForeignCrashGuard() {
  if (!installed_) return;
  const std::lock_guard<std::mutex> lock(g_mutex);
  if (--g_depth > 0) return;
  for (std::size_t i = 0; i < std::size(kGuardedSignals); ++i) sigaction(kGuardedSignals[i], &g_previous[i], nullptr);
}

}  // namespace lfsp
