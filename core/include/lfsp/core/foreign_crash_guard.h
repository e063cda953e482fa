#pragma once

#include <string>

namespace lfsp {

// Some file libraries lfsp relies on crash on malformed files instead of reporting an error: make fuzz found
// libhdf5 1.10 (Debian 12) reading through a null pointer (SIGSEGV) while looking up a name in a corrupt .h5/.mat.
// Their code cannot be fixed from here, so the readers of untrusted files hold this guard while such a library
// parses: a crash (SIGSEGV, SIGBUS, SIGFPE) in that time prints one line, `lfsp: error: FILE: malformed file
// (LIBRARY crashed reading it)`, and exits with status 2, the bad-input status, instead of dying on a signal. A crash
// outside any guard keeps its usual behaviour. Guards nest (the outermost one names the file). In a fuzz build
// (LFSP_FUZZ) the guard does nothing, so that the fuzzer sees and records such crashes.
class ForeignCrashGuard {
 public:
  ForeignCrashGuard(const std::string& path, const char* library);
  ~ForeignCrashGuard();
  ForeignCrashGuard(const ForeignCrashGuard&) = delete;
  ForeignCrashGuard& operator=(const ForeignCrashGuard&) = delete;

 private:
  bool installed_ = false;
};

}  // namespace lfsp
