// Long commands show progress on a terminal and stay quiet otherwise (issue 15, item 13): each command runs with its
// stderr on a pseudo-terminal, whose output must hold the command's progress bar, and through a pipe, whose must not.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "test_support.h"

extern char** environ;

namespace lfsp {
namespace {

namespace fs = std::filesystem;
using testing::RunLfsp;
using testing::TempDir;

// Runs lfsp with stdout to /dev/null and stderr on a new pseudo-terminal; returns what the terminal received.
std::string StderrOnTerminal(const std::vector<std::string>& arguments) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) return "openpty failed";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, slave, 2);
  posix_spawn_file_actions_addclose(&actions, master);
  const char* binary = std::getenv("LFSP_BINARY");
  std::vector<std::string> storage = {binary};
  storage.insert(storage.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& a : storage) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, binary, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(slave);
  std::string received;
  if (spawned == 0) {
    char buffer[4096];
    for (;;) {
      const ssize_t n = read(master, buffer, sizeof buffer);
      if (n > 0) {
        received.append(buffer, static_cast<std::size_t>(n));
      } else if (n < 0 && errno == EINTR) {
        continue;
      } else {
        break;  // EIO once the child has closed the terminal
      }
    }
    int status = 0;
    waitpid(pid, &status, 0);
  }
  close(master);
  return received;
}

TEST(Progress, DrawnOnATerminalOnly) {
  TempDir temp;
  Bundle bundle;
  bundle.light_field = LightField({5, 5, 64, 48, 3});
  for (std::size_t i = 0; i < bundle.light_field.size(); ++i)
    bundle.light_field.data()[i] = static_cast<float>((i * 2654435761u) % 1000) / 1000.0f;
  bundle.disparity = DisparityMap(64, 48, 0.0f);
  bundle.labels = Labels(bundle.light_field.shape(), 0);
  WriteBundle(bundle, temp / "lf.h5");
  const fs::path sample = testing::SourceDir() / "samples" / "mini-illum" / "capture.LFR";
  const std::string lf = (temp / "lf.h5").string();
  const std::vector<std::pair<std::string, std::vector<std::string>>> commands = {
      {"depth [", {"depth", lf, "--dmin", "-1", "--dmax", "1", "--out", (temp / "d.pfm").string()}},
      {"segment [", {"segment", lf, "--out", (temp / "s.h5").string()}},
      {"evaluate [", {"evaluate", "segmentation", lf, "--baselines"}},
      {"decode [", {"decode", sample.string(), "--out", (temp / "dec.h5").string()}},
  };
  for (const auto& [bar, arguments] : commands) {
    SCOPED_TRACE(arguments.front());
    const std::string terminal = StderrOnTerminal(arguments);
    EXPECT_NE(terminal.find(bar), std::string::npos) << terminal;
    EXPECT_NE(terminal.find("100%"), std::string::npos) << terminal;
    const testing::CommandResult piped = RunLfsp(arguments);
    EXPECT_EQ(piped.exit_status, 0) << piped.err;
    EXPECT_EQ(piped.err.find(bar), std::string::npos) << piped.err;
    EXPECT_EQ(piped.err.find('\r'), std::string::npos) << piped.err;
  }
}

}  // namespace
}  // namespace lfsp
