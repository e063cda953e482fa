#pragma once

// The parsers of files (PFM, .mat, images) read paths, not buffers: a fuzz input is written to one temporary file
// per process and parsed from there.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

inline std::filesystem::path FuzzInputFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("lfsp-fuzz-" + std::to_string(getpid()) + extension);
  std::ofstream file(path, std::ios::binary | std::ios::trunc);
  file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}
