// Runs are atomic as a set (issue 15, item 10): SIGKILL at several points of `pipeline` and `decode`, then a rerun,
// leaves exactly one consistent result set and no temporaries; a killed rerun leaves the previous set untouched.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.h"

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::ReadBytes;
using testing::RunLfsp;
using testing::RunLfspKilledAfter;
using testing::TempDir;

// Every path under `folder` (recursively) whose name holds AtomicOutput's temporary tag.
std::vector<fs::path> Temporaries(const fs::path& folder) {
  std::vector<fs::path> found;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) found.push_back(entry.path());
  return found;
}

// The run's summary lists every file it wrote with its size: the folder must hold exactly those.
void ExpectConsistentRun(const fs::path& run) {
  ASSERT_TRUE(fs::exists(run / "summary.json"));
  const nlohmann::json summary = nlohmann::json::parse(ReadBytes(run / "summary.json"));
  const nlohmann::json& sizes = summary["output_bytes"];
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(run)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = fs::relative(entry.path(), run).generic_string();
    if (name == "summary.json") continue;  // written after the sizes were taken
    ++files;
    ASSERT_TRUE(sizes.contains(name)) << name << " is not from this run";
    EXPECT_EQ(sizes[name].get<std::uintmax_t>(), entry.file_size()) << name;
  }
  EXPECT_EQ(files + 1, sizes.size());  // + the "total" entry
}

TEST(Kill, PipelineKilledAtSeveralPointsThenRerun) {
  TempDir temp;
  const fs::path sample = testing::SourceDir() / "samples" / "mini-illum" / "capture.LFR";
  const fs::path run = temp / "run";
  const std::vector<std::string> arguments = {"pipeline", sample.string(), "--out", run.string(), "-q"};
  ASSERT_EQ(RunLfsp(arguments).exit_status, 0);
  ExpectConsistentRun(run);
  const std::string first = ReadBytes(run / "summary.json");

  // The reruns segment differently, so a set mixing old and new files would show in the sizes. They are killed at
  // fractions of the first run's wall time, so that most kills land inside a run on a fast machine and a slow one.
  std::vector<std::string> rerun = arguments;
  rerun.insert(rerun.end(), {"--size", "12"});
  const double wall = nlohmann::json::parse(first)["wall_seconds"].get<double>();
  int killed = 0;
  std::string current = first;
  for (const double fraction : {0.1, 0.3, 0.5, 0.7}) {
    SCOPED_TRACE(fraction);
    if (RunLfspKilledAfter(rerun, fraction * wall)) {
      ++killed;
      EXPECT_EQ(ReadBytes(run / "summary.json"), current) << "a killed run must leave the previous set as it was";
    } else {
      current = ReadBytes(run / "summary.json");  // finished before the kill: its own set replaced the previous one
    }
    ExpectConsistentRun(run);
  }
  EXPECT_GE(killed, 2) << "the runs finished before they could be killed";

  ASSERT_EQ(RunLfsp(rerun).exit_status, 0);
  ExpectConsistentRun(run);
  EXPECT_NE(ReadBytes(run / "summary.json"), first);
  EXPECT_TRUE(Temporaries(temp.path()).empty()) << Temporaries(temp.path()).front();
}

TEST(Kill, DecodeKilledThenRerun) {
  TempDir temp;
  const fs::path sample = testing::SourceDir() / "samples" / "mini-illum" / "capture.LFR";
  const fs::path out = temp / "decoded.h5";
  const std::vector<std::string> arguments = {"decode", sample.string(), "--out", out.string(), "-q"};
  // Timed on another output, so that the kills below land at fractions of a whole run on a fast machine and a slow
  // one (a fixed 0.1-0.5 s could all come after a fast run had finished, and the test would kill nothing); the
  // quicker of two runs, since the first one starts cold.
  double wall = 1e9;
  for (int run = 0; run < 2; ++run) {
    const auto start = std::chrono::steady_clock::now();
    ASSERT_EQ(RunLfsp({"decode", sample.string(), "--out", (temp / "timing.h5").string(), "-q"}).exit_status, 0);
    wall = std::min(wall, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  fs::remove(temp / "timing.h5");
  // A kill can land after the output was renamed into place and before the process ended: then the file is whole.
  const auto whole = [&] { return RunLfsp({"info", out.string()}).exit_status == 0; };

  int killed = 0;
  for (const double fraction : {0.15, 0.3, 0.45}) {
    SCOPED_TRACE(fraction);
    if (!RunLfspKilledAfter(arguments, fraction * wall)) break;  // finished: the reruns below take over
    ++killed;
    if (fs::exists(out)) {
      EXPECT_TRUE(whole()) << "a killed decode must leave no file under the output's name, or a whole one";
      fs::remove(out);
    }
  }
  ASSERT_EQ(RunLfsp(arguments).exit_status, 0);
  const std::string complete = ReadBytes(out);
  for (const double fraction : {0.1, 0.2, 0.4, 0.1, 0.1}) {
    if (killed >= 4) break;
    SCOPED_TRACE(fraction);
    if (RunLfspKilledAfter(arguments, fraction * wall)) {
      ++killed;
      EXPECT_TRUE(ReadBytes(out) == complete || whole()) << "a killed rerun must leave a whole output";
    }
  }
  EXPECT_GE(killed, 2) << "the decodes finished before they could be killed";
  EXPECT_EQ(RunLfsp({"info", out.string()}).exit_status, 0);
  ASSERT_EQ(RunLfsp(arguments).exit_status, 0);
  EXPECT_TRUE(Temporaries(temp.path()).empty()) << Temporaries(temp.path()).front();
}

}  // namespace
}  // namespace lfsp
