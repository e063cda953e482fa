#pragma once

// The parsers of files (PFM, .mat, images) read paths, not buffers: a fuzz input is written to one temporary file
// per process and parsed from there.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <system_error>

// Removes `path` (a file or a folder) when the process exits normally, so a fuzz or replay run leaves nothing in
// the temporary folder (a crash keeps it, beside the crash's reproducer).
inline void RemoveAtExit(const std::filesystem::path& path) {
  struct Removed {
    std::set<std::filesystem::path> paths;
    ~Removed() {
      for (const std::filesystem::path& each : paths) {
        std::error_code ignored;
        std::filesystem::remove_all(each, ignored);
      }
    }
  };
  static Removed removed;
  removed.paths.insert(path);
}

inline std::filesystem::path FuzzInputFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("lfsp-fuzz-" + std::to_string(getpid()) + extension);
  RemoveAtExit(path);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}
