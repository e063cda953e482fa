#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lfsp::decode {

// The Lytro LFP container (.lfp, .lfr, .LFR, calibration archives data.C.N),
// byte layout as in shared/reference/lytro-format.md §1.1:
//   file:    magic "\x89LFP\r\n\x1a\n" 00 00 00 01, uint32 big-endian 0, then
//   sections back to back; section: magic "\x89LFM\r\n\x1a\n" (metadata / table
//   of contents) or "\x89LFC\r\n\x1a\n" (content),
//            4 zero bytes, uint32 big-endian payload length, "sha1-" + 40
//            lowercase hex of the payload, 35 NUL bytes (header = 96 bytes),
//            the payload, NUL padding to the next 16-byte boundary.
// References between sections are the strings "sha1-<hex>" of the referenced
// payload.

enum class SectionKind { kMetadata /* LFM */, kContent /* LFC */ };

std::string_view ToString(SectionKind kind);  // "LFM" / "LFC"

struct LfpSection {
  SectionKind kind = SectionKind::kContent;
  std::vector<std::uint8_t> payload;
  std::string sha1;          // "sha1-<40 lowercase hex>" of the payload
  std::uint64_t offset = 0;  // byte offset of the section header in the file it
                             // was read from (0 if built)

  std::string_view Text() const;                         // the payload as characters (JSON sections)
  nlohmann::json Json(const std::string& source) const;  // parses the payload; lfsp::Error naming source + offset
};

class LfpContainer {
 public:
  std::vector<LfpSection> sections;  // in file order; writing keeps this order

  // Appends a section and returns its reference "sha1-<hex>". The JSON is
  // written as text, tab-indented like the camera's own files.
  std::string AddBinary(std::vector<std::uint8_t> payload, SectionKind kind = SectionKind::kContent);
  std::string AddJson(const nlohmann::json& value, SectionKind kind = SectionKind::kContent);

  // The section whose sha1 equals `reference`, or nullptr.
  const LfpSection* Find(std::string_view reference) const;
  // Same, but throws lfsp::Error naming `source` and `what` (e.g.
  // "frames[0].frame.imageRef") if missing.
  const LfpSection& Resolve(std::string_view reference, const std::string& source, std::string_view what) const;

  // The first LFM section (the table of contents), or nullptr / lfsp::Error
  // naming `source` if there is none.
  const LfpSection* FindToc() const;
  const LfpSection& Toc(const std::string& source) const;

  std::size_t CountOf(SectionKind kind) const;
};

// "sha1-<40 lowercase hex>" of the bytes (OpenSSL SHA-1).
std::string Sha1Reference(std::span<const std::uint8_t> bytes);

// Checks for the LFP file magic (12 bytes) at the start.
bool HasLfpMagic(std::span<const std::uint8_t> bytes);

// Parses a whole container held in memory. Every section is found by its magic
// (NUL padding between sections is skipped), every length is checked against
// the end of the buffer, and every SHA-1 is verified. Any problem (wrong file
// magic, truncated header, length past the end, unknown section magic, SHA-1
// mismatch) throws lfsp::Error naming `source_name`, the section index and its
// byte offset.
LfpContainer ParseLfpContainer(std::span<const std::uint8_t> bytes, const std::string& source_name);
LfpContainer ReadLfpContainer(const std::filesystem::path& path);

// The exact byte layout above, sections in vector order, each padded to 16
// bytes (the last one too). The sha1 field of each section is recomputed from
// its payload (a stale one in `container` is not trusted).
std::vector<std::uint8_t> SerializeLfpContainer(const LfpContainer& container);
// Writes atomically (temporary name, then rename).
void WriteLfpContainer(const LfpContainer& container, const std::filesystem::path& path);

// Whole-file helpers used by the container and raw readers: read all bytes
// (lfsp::Error if unreadable) and write bytes atomically.
std::vector<std::uint8_t> ReadFileBytes(const std::filesystem::path& path);
void WriteFileBytesAtomic(std::span<const std::uint8_t> bytes, const std::filesystem::path& path);

}  // namespace lfsp::decode
