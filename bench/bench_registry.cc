#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include "bench_case.h"

namespace lfsp::bench {
namespace {
std::vector<std::function<BenchCase()>>& Makers() {
  static std::vector<std::function<BenchCase()>> makers;
  return makers;
}
}  // namespace

int RegisterBenchCase(std::function<BenchCase()> make) {
  Makers().push_back(std::move(make));
  return static_cast<int>(Makers().size());
}

// In registration order, except that a case waits for its baseline: the ratio needs the baseline's median, and
// registration follows the link order of the case files, which says nothing about baselines.
std::vector<BenchCase> AllBenchCases() {
  std::vector<BenchCase> cases, waiting;
  std::set<std::string> names;
  const auto append = [&](BenchCase c) {
    names.insert(c.name);
    cases.push_back(std::move(c));
    for (bool released = true; released;) {
      released = false;
      for (auto it = waiting.begin(); it != waiting.end(); ++it)
        if (names.count(it->baseline) != 0) {
          BenchCase ready = std::move(*it);
          waiting.erase(it);
          names.insert(ready.name);
          cases.push_back(std::move(ready));
          released = true;
          break;
        }
    }
  };
  std::set<std::string> all_names;
  std::vector<BenchCase> made;
  for (const auto& make : Makers()) {
    made.push_back(make());
    all_names.insert(made.back().name);
  }
  for (BenchCase& c : made) {
    if (!c.baseline.empty() && names.count(c.baseline) == 0 && all_names.count(c.baseline) != 0)
      waiting.push_back(std::move(c));
    else
      append(std::move(c));
  }
  for (BenchCase& c : waiting) cases.push_back(std::move(c));
  return cases;
}

std::string SharedDataDir() {
  const char* configured = std::getenv("LFSP_SHARED_DATA");
  const std::string path = configured ? configured : LFSP_SHARED_DATA_DEFAULT;
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) ? path : "";
}

}  // namespace lfsp::bench
