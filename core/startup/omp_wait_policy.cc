// lfsp's default OpenMP wait policy, for its executables (`lfsp`, `lfsp_bench`, the tests): passive, unless the user
// set OMP_WAIT_POLICY or GOMP_SPINCOUNT, which then win.
//
// Why: libgomp's own default lets a thread that waits at a barrier spin for about 3 ms before it sleeps. On a
// machine with more busy threads than cores (two lfsp jobs at once, a build, a BLAS program beside us) the thread it
// waits for is often not running, and the spinning takes the very core that thread needs. Two LFSP segmentations of
// antinous started together took 15.8 s against 8.2 s one after the other, and 6.9 s with the passive policy
// (issue 48; BENCHMARKS.md, "Threads under load"). Passive threads sleep on a futex at once and give the core back.
//
// How: libgomp reads its settings with getenv() once, in its own initialiser, before main() runs, so main() is too
// late to set the variable. (An executable's .preinit_array runs earlier, but glibc's own initialiser then puts the
// original environment back before libgomp's runs.) An executable's definition of a function takes precedence over
// a shared library's for every library that calls it (ELF symbol interposition), so this getenv answers libgomp's
// question, and every other caller's, from the environment, with "passive" for OMP_WAIT_POLICY when the user set
// neither variable. Nothing is written into the environment: programs lfsp starts see what the user set. A shared
// library cannot interpose on its host this way, so the Python module sets the variable in lfsp/__init__.py before
// it loads the extension. This file is therefore an object library linked into executables only;
// tests/core/omp_wait_policy_test.cc checks that libgomp really spins for zero rounds.

#include <unistd.h>

#include <cstring>

namespace {

char* FromEnvironment(const char* name) {
  const std::size_t length = std::strlen(name);
  if (length == 0 || std::strchr(name, '=') != nullptr) return nullptr;
  for (char** entry = environ; entry != nullptr && *entry != nullptr; ++entry)
    if (std::strncmp(*entry, name, length) == 0 && (*entry)[length] == '=') return *entry + length + 1;
  return nullptr;
}

}  // namespace

// NOLINTNEXTLINE(bugprone-reserved-identifier,cert-dcl37-c,cert-dcl51-cpp): interposes on the C library's getenv.
extern "C" char* getenv(const char* name) {
  char* value = FromEnvironment(name);
  if (value != nullptr || std::strcmp(name, "OMP_WAIT_POLICY") != 0) return value;
  if (FromEnvironment("GOMP_SPINCOUNT") != nullptr) return nullptr;  // the user tuned the spinning directly
  static char passive[] = "passive";
  return passive;
}
