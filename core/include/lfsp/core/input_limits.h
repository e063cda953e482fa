#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lfsp {

// Sizes declared inside untrusted files (image headers, HDF5 shapes, raw frame sizes) are checked against the bytes
// the file really holds and against a memory cap before anything is allocated for them, so a 74-byte PNG that
// declares 20000 x 20000 pixels is refused instead of costing gigabytes.
//
// The rule, by default: what the declaration would make us allocate must stay under kDefaultMemoryCapBytes and
// under kSlackBytes + kMaxExpansion x the file's size. Genuine light fields stay far inside the ratio: float32 samples
// in memory over bytes on disk measured 10x for antinous's PNG views, 5x for the real Illum field's, about 2.5x for
// the pipeline's bundle of the two-horses Illum decode. A file that claims more is lying about its size or is all
// fill. `--max-memory GIB` replaces both with one cap and
// trusts the declarations below it (for genuine, extremely compressible data).
inline constexpr std::uint64_t kSlackBytes = 64ull << 20;
inline constexpr std::uint64_t kMaxExpansion = 512;
inline constexpr std::uint64_t kDefaultMemoryCapBytes = 16ull << 30;

// Sets the cap of `--max-memory` (bytes); std::nullopt restores the default rule.
void SetMemoryLimit(std::optional<std::uint64_t> bytes);

// Throws lfsp::Error naming `where` when allocating `declared_bytes` for input that occupies `file_bytes` on disk
// breaks the rule above.
void CheckDeclaredAllocation(const std::string& where, std::uint64_t declared_bytes, std::uint64_t file_bytes);

// Throws lfsp::Error "<path>: no such file" or "<path>: not a regular file" unless `path` names a regular file
// (after symbolic links). Every reader calls it before it opens a file: opening a FIFO for reading waits for a writer
// forever, and a device never ends.
void RequireRegularFile(const std::filesystem::path& path);

// The whole of a regular file (RequireRegularFile first); lfsp::Error naming the file if it cannot be read.
std::string ReadWholeFile(const std::filesystem::path& path);

// The size of a file in bytes, 0 when it cannot be read (the reader reports that itself).
std::uint64_t FileBytes(const std::filesystem::path& path);

// Product of dimensions times the element size, saturating at UINT64_MAX instead of wrapping.
std::uint64_t SaturatingBytes(const std::vector<std::uint64_t>& dims, std::uint64_t element_bytes);

}  // namespace lfsp
