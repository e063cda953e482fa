#include "mat5_structure.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

// MAT-file data types (MATLAB's "MAT-File Format", table 1-1) that the checks below look at.
constexpr std::uint32_t kMiInt8 = 1;
constexpr std::uint32_t kMiInt32 = 5;
constexpr std::uint32_t kMiUint32 = 6;
constexpr std::uint32_t kMiMatrix = 14;
constexpr std::uint32_t kMiCompressed = 15;

constexpr std::uint32_t kMaxDimensions = 32;   // far above any light field (5) or any array MATLAB users make
constexpr std::uint32_t kMaxNameBytes = 4096;  // MATLAB's names are at most 63 characters
// Enough of a variable to hold its tag, array flags, dimensions (at most kMaxDimensions) and the start of its name.
constexpr std::size_t kHeaderBytes = 8 + 16 + 8 + 4 * kMaxDimensions + 8;

class WordReader {
 public:
  explicit WordReader(bool swapped) : swapped_(swapped) {}
  std::uint32_t operator()(const unsigned char* b) const {
    return swapped_ ? (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) | (std::uint32_t{b[2]} << 8) | b[3]
                    : (std::uint32_t{b[3]} << 24) | (std::uint32_t{b[2]} << 16) | (std::uint32_t{b[1]} << 8) | b[0];
  }

 private:
  bool swapped_;
};

struct Tag {
  std::uint32_t type = 0;
  std::uint32_t bytes = 0;
  std::size_t size = 8;  // bytes the tag and its data take (the small format packs up to 4 bytes of data in it)
};

// A data element's tag at `at`; the small format keeps the byte count in the upper half of the first word.
Tag ReadTag(const WordReader& word, const unsigned char* at) {
  Tag tag;
  const std::uint32_t first = word(at);
  if ((first >> 16) != 0) {
    tag.type = first & 0xffffu;
    tag.bytes = first >> 16;
    tag.size = 8;
  } else {
    tag.type = first;
    tag.bytes = word(at + 4);
    tag.size = 8 + (static_cast<std::size_t>(tag.bytes) + 7) / 8 * 8;
  }
  return tag;
}

struct InflatedElement {
  std::vector<unsigned char> prefix;  // the first bytes (at most the limit asked for)
  std::uint64_t length = 0;           // all the bytes the stream inflates to
  std::string problem;                // what is wrong with the stream; empty if it is intact and complete
};

// Inflates the whole zlib stream held in `compressed` bytes at `offset` of the file a piece at a time, keeping only
// its first `limit` bytes, so that a lying element costs no memory beyond its prefix. Says what is wrong unless the
// stream is intact and complete: matio reads a damaged stream as zeros without a word (a .mat with flipped bytes
// inside its compressed light field came back mostly black), so zlib's own check (Adler-32 of the inflated bytes)
// must pass and the stream must end where the element does.
InflatedElement InflateElement(std::ifstream& file, std::uint64_t offset, std::uint32_t compressed, std::size_t limit,
                               const std::string& name) {
  InflatedElement result;
  result.prefix.resize(limit);
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) ThrowFileError(name, "cannot start zlib");
  std::array<unsigned char, 1 << 16> chunk{};
  std::array<unsigned char, 1 << 16> scratch{};
  std::uint64_t left = compressed;
  file.seekg(static_cast<std::streamoff>(offset));
  int status = Z_OK;
  while (status == Z_OK && left > 0) {
    const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(left, chunk.size()));
    if (!file.read(reinterpret_cast<char*>(chunk.data()), static_cast<std::streamsize>(take))) break;
    left -= take;
    stream.next_in = chunk.data();
    stream.avail_in = static_cast<uInt>(take);
    while (stream.avail_in > 0 && status == Z_OK) {
      // The prefix first, then the scratch buffer, whose bytes are only counted.
      const bool in_prefix = result.length < limit;
      unsigned char* target = in_prefix ? result.prefix.data() + result.length : scratch.data();
      const std::size_t room = in_prefix ? limit - static_cast<std::size_t>(result.length) : scratch.size();
      stream.next_out = target;
      stream.avail_out = static_cast<uInt>(room);
      status = inflate(&stream, Z_NO_FLUSH);
      result.length += room - stream.avail_out;
      if (status == Z_BUF_ERROR && stream.avail_out > 0) status = Z_OK;  // needs more input: the outer loop reads it
    }
  }
  const bool consumed_all = left == 0 && stream.avail_in == 0;
  if (status == Z_DATA_ERROR)
    result.problem = "is corrupt (zlib: " + std::string(stream.msg != nullptr ? stream.msg : "data error") + ")";
  else if (status != Z_STREAM_END)
    result.problem = "is cut off: its zlib stream does not end inside the element";
  else if (!consumed_all)
    result.problem = "has bytes after the end of its zlib stream";
  inflateEnd(&stream);
  result.prefix.resize(static_cast<std::size_t>(std::min<std::uint64_t>(result.length, limit)));
  return result;
}

// The inflated element must be exactly its tag and the bytes the tag declares (a short stream would leave matio to
// fill the rest with zeros).
void CheckInflatedLength(const WordReader& word, const InflatedElement& element, std::uint64_t offset,
                         const std::string& name) {
  if (element.prefix.size() < 8)
    ThrowFileError(name, "compressed variable at byte " + std::to_string(offset) + " inflates to " +
                             std::to_string(element.length) + " bytes");
  const Tag tag = ReadTag(word, element.prefix.data());
  if (element.length != tag.size && element.length != 8 + std::uint64_t{tag.bytes})
    ThrowFileError(name, "compressed variable at byte " + std::to_string(offset) + " inflates to " +
                             std::to_string(element.length) + " bytes, but its element declares " +
                             std::to_string(8 + std::uint64_t{tag.bytes}));
}

// Checks the header of the variable (a miMATRIX element) in `element`, which starts at its tag; `offset` names it.
void CheckVariableHeader(const WordReader& word, const std::vector<unsigned char>& element, std::uint64_t offset,
                         const std::string& name) {
  const auto where = [&] { return "the variable at byte " + std::to_string(offset); };
  if (element.size() < 8 || ReadTag(word, element.data()).type != kMiMatrix) return;  // not a variable: matio's call
  std::size_t at = 8;
  if (element.size() < at + 8) return;  // an empty matrix element
  const Tag flags = ReadTag(word, element.data() + at);
  if (flags.type != kMiUint32) ThrowFileError(name, where() + " has no array flags");
  at += flags.size;
  if (element.size() < at + 8) ThrowFileError(name, where() + " ends inside its header");
  const Tag dims = ReadTag(word, element.data() + at);
  if (dims.type != kMiInt32 || dims.bytes % 4 != 0 || dims.bytes / 4 > kMaxDimensions)
    ThrowFileError(name, where() + " declares a dimensions array of " + std::to_string(dims.bytes) +
                             " bytes (at most " + std::to_string(kMaxDimensions) + " int32 dimensions)");
  at += dims.size;
  if (element.size() < at + 8) return;  // the name lies past the prefix that was read: short enough by then
  const Tag variable_name = ReadTag(word, element.data() + at);
  if (variable_name.type != kMiInt8 || variable_name.bytes > kMaxNameBytes)
    ThrowFileError(name, where() + " declares a name of " + std::to_string(variable_name.bytes) + " bytes");
}

}  // namespace

void CheckMat5Structure(const fs::path& path) {
  const std::string name = path.string();
  std::ifstream file(path, std::ios::binary);
  const std::uint64_t size = FileBytes(path);
  char header[128];
  if (!file.read(header, sizeof header)) ThrowFileError(name, "not a MATLAB .mat file (shorter than its header)");
  const bool swapped = header[126] == 'M' && header[127] == 'I';  // written on a machine of the other byte order
  if (!swapped && !(header[126] == 'I' && header[127] == 'M'))
    ThrowFileError(name, "not a MATLAB v5 .mat file (no endian mark at byte 126)");
  const WordReader word(swapped);
  std::uint64_t offset = 128;
  unsigned char tag[8];
  while (offset < size) {
    file.seekg(static_cast<std::streamoff>(offset));
    if (!file.read(reinterpret_cast<char*>(tag), 8))
      ThrowFileError(name, "truncated .mat: a data element's tag at byte " + std::to_string(offset) + " is cut off");
    const std::uint32_t type = word(tag), bytes = word(tag + 4);
    if (offset + 8 + bytes > size)
      ThrowFileError(name, "truncated .mat: the data element at byte " + std::to_string(offset) + " declares " +
                               std::to_string(bytes) + " bytes, past the end of the file (" + std::to_string(size) +
                               " bytes)");
    if (type == kMiCompressed) {
      const InflatedElement element = InflateElement(file, offset + 8, bytes, kHeaderBytes, name);
      CheckVariableHeader(word, element.prefix, offset, name);  // first: what the header declares is more telling
      if (!element.problem.empty())
        ThrowFileError(name, "compressed variable at byte " + std::to_string(offset) + " " + element.problem);
      CheckInflatedLength(word, element, offset, name);
    } else if (type == kMiMatrix) {
      std::vector<unsigned char> element(std::min<std::uint64_t>(kHeaderBytes, 8 + bytes));
      file.seekg(static_cast<std::streamoff>(offset));
      if (!file.read(reinterpret_cast<char*>(element.data()), static_cast<std::streamsize>(element.size())))
        ThrowFileError(name, "cannot read the variable at byte " + std::to_string(offset));
      CheckVariableHeader(word, element, offset, name);
    }
    std::uint64_t end = offset + 8 + bytes;
    if (type != kMiCompressed) end = (end + 7) / 8 * 8;  // miCOMPRESSED elements are not padded
    offset = end;
  }
}

}  // namespace lfsp
