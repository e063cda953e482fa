#include "lfsp/decode/lfp_container.h"

#include <openssl/evp.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <string>

#include "json_text.h"
#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"

namespace lfsp::decode {
namespace {

constexpr std::array<std::uint8_t, 12> kFileMagic = {0x89, 'L', 'F', 'P', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 1};
constexpr std::array<std::uint8_t, 8> kMetadataMagic = {0x89, 'L', 'F', 'M', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::array<std::uint8_t, 8> kContentMagic = {0x89, 'L', 'F', 'C', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::size_t kFileHeaderSize = 16;
constexpr std::size_t kSectionHeaderSize = 96;
constexpr std::size_t kLengthOffset = 12;
constexpr std::size_t kSha1Offset = 16;
constexpr std::size_t kSha1FieldSize = 45;  // "sha1-" + 40 hex
constexpr std::size_t kAlignment = 16;

std::uint32_t ReadBigEndian32(const std::uint8_t* p) {
  return (static_cast<std::uint32_t>(p[0]) << 24) | (static_cast<std::uint32_t>(p[1]) << 16) |
         (static_cast<std::uint32_t>(p[2]) << 8) | static_cast<std::uint32_t>(p[3]);
}

void AppendBigEndian32(std::vector<std::uint8_t>& out, std::uint32_t value) {
  out.push_back(static_cast<std::uint8_t>(value >> 24));
  out.push_back(static_cast<std::uint8_t>(value >> 16));
  out.push_back(static_cast<std::uint8_t>(value >> 8));
  out.push_back(static_cast<std::uint8_t>(value));
}

bool StartsWith(std::span<const std::uint8_t> bytes, std::size_t offset, std::span<const std::uint8_t> magic) {
  return bytes.size() >= offset + magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin() + offset);
}

std::string SectionWhere(const std::string& source, std::size_t index, std::size_t offset) {
  return source + ": section " + std::to_string(index) + " at byte offset " + std::to_string(offset);
}

// Reads one section starting at `offset` (its magic already located there) and
// returns the offset after it.
std::size_t ParseSection(std::span<const std::uint8_t> bytes, std::size_t offset, std::size_t index,
                         const std::string& source, LfpSection& section) {
  const std::string where = SectionWhere(source, index, offset);
  if (StartsWith(bytes, offset, kMetadataMagic)) {
    section.kind = SectionKind::kMetadata;
  } else if (StartsWith(bytes, offset, kContentMagic)) {
    section.kind = SectionKind::kContent;
  } else {
    throw Error(where + ": wrong section magic (expected \\x89LFM or \\x89LFC)");
  }
  if (bytes.size() - offset < kSectionHeaderSize) {
    throw Error(where + ": truncated section header (" + std::to_string(bytes.size() - offset) +
                " bytes left, the header needs " + std::to_string(kSectionHeaderSize) + ")");
  }
  const std::uint64_t length = ReadBigEndian32(bytes.data() + offset + kLengthOffset);
  const std::uint64_t payload_offset = offset + kSectionHeaderSize;
  if (length > bytes.size() - payload_offset) {
    throw Error(where + ": payload length " + std::to_string(length) + " goes past the end of the file (" +
                std::to_string(bytes.size() - payload_offset) + " bytes left)");
  }
  const std::string sha1_field(reinterpret_cast<const char*>(bytes.data() + offset + kSha1Offset), kSha1FieldSize);
  const auto hex_ok = [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); };
  if (sha1_field.rfind("sha1-", 0) != 0 || !std::all_of(sha1_field.begin() + 5, sha1_field.end(), hex_ok)) {
    throw Error(where +
                ": malformed SHA-1 field (expected \"sha1-\" and 40 "
                "lowercase hex digits)");
  }
  const auto payload = bytes.subspan(payload_offset, length);
  const std::string actual = Sha1Reference(payload);
  if (actual != sha1_field) {
    throw Error(where + ": SHA-1 mismatch: the header says " + sha1_field + " but the " + std::to_string(length) +
                "-byte payload hashes to " + actual);
  }
  section.payload.assign(payload.begin(), payload.end());
  section.sha1 = sha1_field;
  section.offset = offset;
  return payload_offset + length;
}

}  // namespace

std::string_view ToString(SectionKind kind) { return kind == SectionKind::kMetadata ? "LFM" : "LFC"; }

std::string_view LfpSection::Text() const { return {reinterpret_cast<const char*>(payload.data()), payload.size()}; }

nlohmann::json LfpSection::Json(const std::string& source) const {
  return ParseLytroJson(Text(), source + ": section at byte offset " + std::to_string(offset) + " (" + sha1 + ")");
}

std::string LfpContainer::AddBinary(std::vector<std::uint8_t> payload, SectionKind kind) {
  LfpSection section;
  section.kind = kind;
  section.sha1 = Sha1Reference(payload);
  section.payload = std::move(payload);
  sections.push_back(std::move(section));
  return sections.back().sha1;
}

std::string LfpContainer::AddJson(const nlohmann::json& value, SectionKind kind) {
  const std::string text = value.dump(1, '\t');
  return AddBinary(std::vector<std::uint8_t>(text.begin(), text.end()), kind);
}

const LfpSection* LfpContainer::Find(std::string_view reference) const {
  for (const LfpSection& section : sections) {
    if (section.sha1 == reference) return &section;
  }
  return nullptr;
}

const LfpSection& LfpContainer::Resolve(std::string_view reference, const std::string& source,
                                        std::string_view what) const {
  const LfpSection* section = Find(reference);
  if (section == nullptr) {
    throw Error(source + ": " + std::string(what) + " refers to " + std::string(reference) +
                ", but no section has that SHA-1");
  }
  return *section;
}

const LfpSection* LfpContainer::FindToc() const {
  for (const LfpSection& section : sections) {
    if (section.kind == SectionKind::kMetadata) return &section;
  }
  return nullptr;
}

const LfpSection& LfpContainer::Toc(const std::string& source) const {
  const LfpSection* toc = FindToc();
  if (toc == nullptr) throw Error(source + ": no LFM (table of contents) section");
  return *toc;
}

std::size_t LfpContainer::CountOf(SectionKind kind) const {
  return static_cast<std::size_t>(
      std::count_if(sections.begin(), sections.end(), [kind](const LfpSection& s) { return s.kind == kind; }));
}

std::string Sha1Reference(std::span<const std::uint8_t> bytes) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int digest_size = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &digest_size, EVP_sha1(), nullptr) != 1 || digest_size != 20) {
    throw std::runtime_error("OpenSSL SHA-1 failed");
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out = "sha1-";
  for (unsigned int i = 0; i < digest_size; ++i) {
    out.push_back(kHex[digest[i] >> 4]);
    out.push_back(kHex[digest[i] & 0x0F]);
  }
  return out;
}

bool HasLfpMagic(std::span<const std::uint8_t> bytes) { return StartsWith(bytes, 0, kFileMagic); }

LfpContainer ParseLfpContainer(std::span<const std::uint8_t> bytes, const std::string& source_name) {
  if (bytes.size() < kFileHeaderSize) {
    throw Error(source_name + ": truncated LFP file (" + std::to_string(bytes.size()) +
                " bytes, the file header alone needs " + std::to_string(kFileHeaderSize) + ")");
  }
  if (!HasLfpMagic(bytes)) throw Error(source_name + ": wrong file magic (not a Lytro LFP/LFR container)");
  // The file header's own length field is 0 in every known file; honour it
  // anyway.
  const std::uint64_t header_payload = ReadBigEndian32(bytes.data() + kLengthOffset);
  if (header_payload > bytes.size() - kFileHeaderSize) {
    throw Error(source_name + ": file header length " + std::to_string(header_payload) +
                " goes past the end of the file");
  }
  LfpContainer container;
  std::size_t offset = kFileHeaderSize + header_payload;
  for (;;) {
    // Sections are 16-byte aligned with NUL padding between them; skip it.
    while (offset < bytes.size() && bytes[offset] == 0) ++offset;
    if (offset >= bytes.size()) break;
    LfpSection section;
    offset = ParseSection(bytes, offset, container.sections.size(), source_name, section);
    container.sections.push_back(std::move(section));
  }
  if (container.sections.empty()) throw Error(source_name + ": LFP file holds no sections");
  return container;
}

LfpContainer ReadLfpContainer(const std::filesystem::path& path) {
  const std::vector<std::uint8_t> bytes = ReadFileBytes(path);
  return ParseLfpContainer(bytes, path.string());
}

std::vector<std::uint8_t> SerializeLfpContainer(const LfpContainer& container) {
  std::size_t total = kFileHeaderSize;
  for (const LfpSection& section : container.sections) {
    if (section.payload.size() > 0xFFFFFFFFu) {
      throw Error("LFP section of " + std::to_string(section.payload.size()) +
                  " bytes does not fit the 32-bit length field");
    }
    total += (kSectionHeaderSize + section.payload.size() + kAlignment - 1) / kAlignment * kAlignment;
  }
  std::vector<std::uint8_t> out;
  out.reserve(total);
  out.insert(out.end(), kFileMagic.begin(), kFileMagic.end());
  AppendBigEndian32(out, 0);
  for (const LfpSection& section : container.sections) {
    const auto& magic = section.kind == SectionKind::kMetadata ? kMetadataMagic : kContentMagic;
    out.insert(out.end(), magic.begin(), magic.end());
    AppendBigEndian32(out, 0);
    AppendBigEndian32(out, static_cast<std::uint32_t>(section.payload.size()));
    const std::string sha1 = Sha1Reference(section.payload);
    out.insert(out.end(), sha1.begin(), sha1.end());
    out.resize(out.size() + (kSectionHeaderSize - kSha1Offset - kSha1FieldSize), 0);
    out.insert(out.end(), section.payload.begin(), section.payload.end());
    out.resize((out.size() + kAlignment - 1) / kAlignment * kAlignment, 0);
  }
  return out;
}

void WriteLfpContainer(const LfpContainer& container, const std::filesystem::path& path) {
  WriteFileBytesAtomic(SerializeLfpContainer(container), path);
}

std::vector<std::uint8_t> ReadFileBytes(const std::filesystem::path& path) {
  RequireRegularFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path.string() + ": cannot open for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(path.string() + ": cannot determine the file size");
  in.seekg(0, std::ios::beg);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), size);
  if (in.gcount() != size) throw Error(path.string() + ": read error");
  return bytes;
}

void WriteFileBytesAtomic(std::span<const std::uint8_t> bytes, const std::filesystem::path& path) {
  AtomicOutput output(path);
  {
    std::ofstream out(output.temporary(), std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path.string() + ": cannot open a temporary file for writing");
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw Error(path.string() + ": write failed (disk full?)");
  }
  output.Commit();
}

}  // namespace lfsp::decode
