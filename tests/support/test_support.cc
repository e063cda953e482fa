#include "test_support.h"

#include <fcntl.h>
#include <pty.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <thread>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "lfsp/core/error.h"

extern char** environ;

namespace lfsp::testing {
namespace fs = std::filesystem;

std::optional<fs::path> SharedDataDir() {
  const char* configured = std::getenv("LFSP_SHARED_DATA");
  if (configured == nullptr) return std::nullopt;
  std::error_code ec;
  if (!fs::is_directory(configured, ec)) return std::nullopt;
  return fs::path(configured);
}

fs::path SourceDir() {
  const char* configured = std::getenv("LFSP_SOURCE_DIR");
  return configured ? fs::path(configured) : fs::current_path();
}

TempDir::TempDir() {
  std::random_device device;
  path_ = fs::temp_directory_path() / ("lfsp-test-" + std::to_string(device()) + std::to_string(device()));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

namespace {

// Starts the built lfsp with the arguments and the given redirections (which it destroys); returns its pid.
// Spawned directly (no shell) so that wait4 reports the command's own peak memory, and a kill reaches lfsp.
pid_t SpawnLfsp(const std::vector<std::string>& arguments, posix_spawn_file_actions_t& actions) {
  const char* binary = std::getenv("LFSP_BINARY");
  if (binary == nullptr) throw std::runtime_error("LFSP_BINARY is not set (run the test through ctest)");
  std::vector<std::string> argv_storage = {binary};
  argv_storage.insert(argv_storage.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& argument : argv_storage) argv.push_back(argument.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, binary, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error(std::string("cannot start ") + binary);
  return pid;
}

// Starts lfsp with stdout and stderr to the given files.
pid_t SpawnLfsp(const std::vector<std::string>& arguments, const std::string& out_path, const std::string& err_path) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  return SpawnLfsp(arguments, actions);
}

int WaitFor(pid_t pid, struct rusage& usage) {
  int status = 0;
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  return status;
}

}  // namespace

CommandResult RunLfsp(const std::vector<std::string>& arguments) {
  TempDir capture;
  const std::string out_path = (capture.path() / "out").string(), err_path = (capture.path() / "err").string();
  const pid_t pid = SpawnLfsp(arguments, out_path, err_path);
  struct rusage usage {};
  const int status = WaitFor(pid, usage);
  CommandResult result;
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.peak_rss_kb = usage.ru_maxrss;
  result.out = ReadBytes(out_path);
  result.err = ReadBytes(err_path);
  return result;
}

std::string RunLfspWithStderrOnTerminal(const std::vector<std::string>& arguments) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) throw std::runtime_error("openpty failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, slave, 2);
  posix_spawn_file_actions_addclose(&actions, master);
  const pid_t pid = SpawnLfsp(arguments, actions);
  close(slave);
  std::string received;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof buffer);
    if (n > 0) {
      received.append(buffer, static_cast<std::size_t>(n));
    } else if (!(n < 0 && errno == EINTR)) {
      break;  // EIO once the command has closed the terminal
    }
  }
  struct rusage usage {};
  WaitFor(pid, usage);
  close(master);
  return received;
}

bool RunLfspKilledAfter(const std::vector<std::string>& arguments, double seconds) {
  TempDir capture;
  const pid_t pid = SpawnLfsp(arguments, (capture.path() / "out").string(), (capture.path() / "err").string());
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
  const bool running = kill(pid, SIGKILL) == 0;
  struct rusage usage {};
  const int status = WaitFor(pid, usage);
  return running && WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream file(path, std::ios::binary);
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream content;
  content << file.rdbuf();
  return content.str();
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("NOT lfsp::Error: ") + e.what();
  }
  return "no error";
}

nlohmann::json LoadJson(const fs::path& path) {
  const std::string text = ReadBytes(path);
  return nlohmann::json::parse(text.substr(0, text.rfind('}') + 1));
}

}  // namespace lfsp::testing
