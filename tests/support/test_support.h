#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace lfsp::testing {

// ../shared/data (LFSP_SHARED_DATA set by CTest), or nothing if absent. Tests that need it call
// LFSP_REQUIRE_SHARED_DATA() which skips with a clear message when the folder is missing.
std::optional<std::filesystem::path> SharedDataDir();

#define LFSP_REQUIRE_SHARED_DATA(var)                                                                         \
  const auto var##_optional = ::lfsp::testing::SharedDataDir();                                               \
  if (!var##_optional) GTEST_SKIP() << "../shared/data not found (LFSP_SHARED_DATA): real-data test skipped"; \
  const std::filesystem::path var = *var##_optional

// The repository root (LFSP_SOURCE_DIR), for bundled samples.
std::filesystem::path SourceDir();
// What a test says when a bundled sample is missing: they are committed, so SourceDir() is wrong, not the test.
inline constexpr const char* kMissingSample = "a bundled sample (samples/) is missing: is LFSP_SOURCE_DIR right?";

// A fresh empty folder under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Runs the built `lfsp` executable (LFSP_BINARY) with the arguments; captures exit status, stdout, stderr and the
// command's peak resident memory.
struct CommandResult {
  int exit_status = -1;
  long peak_rss_kb = 0;
  std::string out;
  std::string err;
};
CommandResult RunLfsp(const std::vector<std::string>& arguments);

// Runs lfsp with stdout to /dev/null and stderr on a new pseudo-terminal; returns what the terminal received.
std::string RunLfspWithStderrOnTerminal(const std::vector<std::string>& arguments);

// Starts lfsp with the arguments and sends it SIGKILL after `seconds`; true when it was killed (false when it had
// already finished).
bool RunLfspKilledAfter(const std::vector<std::string>& arguments, double seconds);

void WriteBytes(const std::filesystem::path& path, const std::string& bytes);
std::string ReadBytes(const std::filesystem::path& path);

// The message of the lfsp::Error that `f` throws, "NOT lfsp::Error: <what>" for any other exception (so a test of
// error messages fails readably instead of aborting), or "no error".
std::string ErrorOf(const std::function<void()>& f);

// A JSON file, up to its last '}': the reference metadata files end in padding that is not JSON.
nlohmann::json LoadJson(const std::filesystem::path& path);

}  // namespace lfsp::testing
