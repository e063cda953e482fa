#include <cstdlib>
#include <filesystem>

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

std::vector<BenchCase> AllBenchCases() {
  std::vector<BenchCase> cases;
  for (const auto& make : Makers()) cases.push_back(make());
  return cases;
}

std::string SharedDataDir() {
  const char* configured = std::getenv("LFSP_SHARED_DATA");
  const std::string path = configured ? configured : LFSP_SHARED_DATA_DEFAULT;
  std::error_code ec;
  return std::filesystem::is_directory(path, ec) ? path : "";
}

}  // namespace lfsp::bench
