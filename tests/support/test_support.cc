#include "test_support.h"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

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
std::string ShellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}
}  // namespace

CommandResult RunLfsp(const std::vector<std::string>& arguments) {
  const char* binary = std::getenv("LFSP_BINARY");
  if (binary == nullptr) throw std::runtime_error("LFSP_BINARY is not set (run the test through ctest)");
  TempDir capture;
  std::string command = ShellQuote(binary);
  for (const auto& argument : arguments) command += " " + ShellQuote(argument);
  command +=
      " >" + ShellQuote((capture.path() / "out").string()) + " 2>" + ShellQuote((capture.path() / "err").string());
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadBytes(capture.path() / "out");
  result.err = ReadBytes(capture.path() / "err");
  return result;
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

}  // namespace lfsp::testing
