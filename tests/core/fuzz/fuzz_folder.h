#pragma once

// The readers of folders (views folders, white-image folders) read many files by name: a fuzz input is unpacked into
// one temporary folder per process, a file per entry, and the reader is given the folder.
//
// Input format: entries, each "@@ NAME\n" followed by the file's bytes up to the next "\n@@ " (or the end):
//
//   @@ input_Cam000.png
//   <bytes>
//   @@ parameters.cfg
//   <bytes>
//
// Names are made harmless rather than refused, so that every input makes a folder: '/' is kept only where
// `subfolders` allows it (then "", "." and ".." components are dropped), other control characters and a leading
// '.' or '-' become '_', names are cut to 100 bytes, and at most kMaxFuzzFolderEntries entries are written (a later
// entry of the same name replaces the earlier). Bytes before the first "@@ " are ignored.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "fuzz_file.h"

inline constexpr std::size_t kMaxFuzzFolderEntries = 128;
inline constexpr std::size_t kMaxFuzzFolderNameBytes = 100;

// One file of a folder input: its (sanitized, relative) name and its bytes.
struct FuzzFolderEntry {
  std::string name;
  std::string_view bytes;
};

inline std::string SanitizedFuzzComponent(std::string_view component) {
  std::string name(component.substr(0, kMaxFuzzFolderNameBytes));
  for (char& c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f || c == '/' || c == '\\') c = '_';
  }
  if (!name.empty() && (name[0] == '.' || name[0] == '-')) name[0] = '_';
  return name;
}

// The entries of `input` in order (names sanitized; entries whose name is empty are dropped).
inline std::vector<FuzzFolderEntry> SplitFuzzFolder(std::string_view input, bool subfolders) {
  constexpr std::string_view kFirst = "@@ ";
  constexpr std::string_view kNext = "\n@@ ";
  std::vector<FuzzFolderEntry> entries;
  std::size_t at = kFirst.size();
  if (input.substr(0, kFirst.size()) != kFirst) {
    at = input.find(kNext);
    if (at == std::string_view::npos) return entries;
    at += kNext.size();
  }
  while (entries.size() < kMaxFuzzFolderEntries) {
    const std::size_t end = input.find(kNext, at);
    const std::string_view chunk = input.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at);
    const std::size_t line = chunk.find('\n');
    const std::string_view raw_name = chunk.substr(0, line);
    const std::string_view bytes = line == std::string_view::npos ? std::string_view() : chunk.substr(line + 1);
    std::string name;
    if (subfolders) {
      std::size_t start = 0;
      while (start <= raw_name.size() && name.size() < kMaxFuzzFolderNameBytes) {
        const std::size_t slash = raw_name.find('/', start);
        const std::string_view part =
            raw_name.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
        if (!part.empty() && part != "." && part != "..")
          name += (name.empty() ? "" : "/") + SanitizedFuzzComponent(part);
        if (slash == std::string_view::npos) break;
        start = slash + 1;
      }
    } else {
      name = SanitizedFuzzComponent(raw_name);
    }
    if (!name.empty()) entries.push_back({std::move(name), bytes});
    if (end == std::string_view::npos) break;
    at = end + kNext.size();
  }
  return entries;
}

// Unpacks `data` (the format above) into a fresh folder, the same one for every input of this process (removed at
// exit), and returns it. `subfolders`: names may hold '/' (the white-image folder is searched recursively).
inline std::filesystem::path FuzzInputFolder(const std::uint8_t* data, std::size_t size, const std::string& tag,
                                             bool subfolders = false) {
  namespace fs = std::filesystem;
  static const fs::path root = [&tag] {
    const fs::path path = fs::temp_directory_path() / ("lfsp-fuzz-" + tag + "-" + std::to_string(getpid()));
    RemoveAtExit(path);
    return path;
  }();
  std::error_code ignored;
  fs::remove_all(root, ignored);
  fs::create_directories(root);
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  for (const FuzzFolderEntry& entry : SplitFuzzFolder(input, subfolders)) {
    const fs::path path = root / entry.name;
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec || fs::is_directory(path, ec)) continue;  // "a" after "a/b": the folder stays
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(entry.bytes.data(), static_cast<std::streamsize>(entry.bytes.size()));
  }
  return root;
}
