#include "lfsp/core/input_limits.h"

#include <atomic>
#include <fstream>
#include <limits>
#include <sstream>

#include "lfsp/core/error.h"

namespace lfsp {
namespace {

// 0 = the default rule; otherwise the cap set by --max-memory.
std::atomic<std::uint64_t> g_explicit_cap{0};

std::string Megabytes(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

}  // namespace

void SetMemoryLimit(std::optional<std::uint64_t> bytes) {
  g_explicit_cap = bytes ? std::max<std::uint64_t>(*bytes, 1) : 0;
}

void CheckDeclaredAllocation(const std::string& where, std::uint64_t declared_bytes, std::uint64_t file_bytes) {
  if (const std::uint64_t cap = g_explicit_cap; cap != 0) {
    if (declared_bytes > cap)
      ThrowFileError(where, "declares " + Megabytes(declared_bytes) + " of samples, above the " +
                                OptionName("max_memory") + " limit of " + Megabytes(cap));
    return;
  }
  if (declared_bytes > kDefaultMemoryCapBytes)
    ThrowFileError(where, "declares " + Megabytes(declared_bytes) + " of samples, above the limit of " +
                              Megabytes(kDefaultMemoryCapBytes) + " (raise it with " + OptionName("max_memory") + ")");
  const std::uint64_t plausible = file_bytes > (std::numeric_limits<std::uint64_t>::max() - kSlackBytes) / kMaxExpansion
                                      ? std::numeric_limits<std::uint64_t>::max()
                                      : kSlackBytes + kMaxExpansion * file_bytes;
  if (declared_bytes > plausible)
    ThrowFileError(where, "declares " + Megabytes(declared_bytes) + " of samples but the file holds only " +
                              std::to_string(file_bytes) +
                              " bytes: the declared size is not plausible (if the data is genuine, raise " +
                              OptionName("max_memory") + " to trust it)");
}

void RequireRegularFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_regular_file(path, ec)) return;
  ThrowFileError(path.string(), std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
}

std::string ReadWholeFile(const std::filesystem::path& path) {
  RequireRegularFile(path);
  std::ifstream file(path, std::ios::binary);
  if (!file) ThrowFileError(path.string(), "cannot open");
  std::ostringstream content;
  content << file.rdbuf();
  if (file.bad()) ThrowFileError(path.string(), "read error");
  return content.str();
}

std::uint64_t FileBytes(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  return ec ? 0 : static_cast<std::uint64_t>(size);
}

std::uint64_t SaturatingBytes(const std::vector<std::uint64_t>& dims, std::uint64_t element_bytes) {
  std::uint64_t total = element_bytes;
  for (std::uint64_t d : dims) {
    if (d != 0 && total > std::numeric_limits<std::uint64_t>::max() / d)
      return std::numeric_limits<std::uint64_t>::max();
    total *= d;
  }
  return total;
}

}  // namespace lfsp
