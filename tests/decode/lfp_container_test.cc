// The LFP container: the four real files (section counts, SHA-1s, byte-exact re-serialisation), synthetic round
// trips through the writer, and one clear lfsp::Error for each kind of damage.

#include "lfsp/decode/lfp_container.h"

#include <gtest/gtest.h>

#include <random>

#include "lfsp/core/error.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

using lfsp::testing::ErrorOf;
using lfsp::testing::TempDir;

struct RealFile {
  const char* name;
  std::size_t sections;
  std::size_t lfm;
  const char* toc_sha1;
};

// Counted with an independent section walker (python, every SHA-1 checked) when the data was added.
constexpr RealFile kRealFiles[] = {
    {"IMG_0001-stk.lfp", 14, 1, "sha1-60ea930b5ee0"},
    {"IMG_0002-dm.lfp", 3, 1, "sha1-14945d6ae97d"},
    {"IMG_0002-stk.lfp", 4, 1, "sha1-2e00c2e800c6"},
    {"illum_demo.LFP", 12, 1, "sha1-8fb0b328e80d"},
};

std::vector<std::uint8_t> RandomBytes(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<std::uint8_t> bytes(n);
  for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
  return bytes;
}

// An Illum-style container: content sections first, the table of contents last.
LfpContainer SyntheticContainer() {
  LfpContainer c;
  const std::string raw = c.AddBinary(RandomBytes(100'003, 1));
  const std::string empty = c.AddBinary({});
  const std::string one = c.AddBinary({0x42});
  const std::string meta = c.AddJson({{"image", {{"width", 3}}}});
  nlohmann::json toc = {{"frames", {{{"frame", {{"imageRef", raw}, {"metadataRef", meta}}}}}}, {"extra", {empty, one}}};
  c.AddJson(toc, SectionKind::kMetadata);
  return c;
}

std::uint32_t BigEndianAt(const std::vector<std::uint8_t>& b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) | (std::uint32_t{b[at + 2]} << 8) | b[at + 3];
}

TEST(Sha1, KnownVector) {
  const std::string abc = "abc";
  EXPECT_EQ(Sha1Reference(std::span(reinterpret_cast<const std::uint8_t*>(abc.data()), abc.size())),
            "sha1-a9993e364706816aba3e25717850c26c9cd0d89d");
}

TEST(LfpContainerReal, SectionCountsShaAndExactReserialisation) {
  LFSP_REQUIRE_SHARED_DATA(data);
  for (const RealFile& real : kRealFiles) {
    SCOPED_TRACE(real.name);
    const auto path = data / "lytro" / real.name;
    const LfpContainer c = ReadLfpContainer(path);
    EXPECT_EQ(c.sections.size(), real.sections);
    EXPECT_EQ(c.CountOf(SectionKind::kMetadata), real.lfm);
    EXPECT_EQ(c.sections.front().kind, SectionKind::kMetadata);  // these four put the LFM first
    EXPECT_EQ(c.sections.front().sha1.substr(0, 17), real.toc_sha1);
    // Every section's SHA-1 was checked by the reader (it throws on a mismatch: Sha1MismatchNamesSectionAndOffset;
    // its hash: Sha1.KnownVector); the first one's prefix above comes from a separate walker of the files.
    for (const LfpSection& s : c.sections) EXPECT_EQ(s.offset % 16, 0u);
    // The writer reproduces the real byte layout exactly (headers, lengths, padding).
    EXPECT_TRUE(SerializeLfpContainer(c) == ReadFileBytes(path));
  }
}

TEST(LfpContainerReal, TocIsJsonOfTheExpectedSchema) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const LfpContainer illum = ReadLfpContainer(data / "lytro" / "illum_demo.LFP");
  const nlohmann::json toc = illum.Toc("illum").Json("illum");
  EXPECT_EQ(toc["frames"][0]["frame"]["metadata"]["camera"]["model"], "ILLUM");
  const LfpContainer f01 = ReadLfpContainer(data / "lytro" / "IMG_0001-stk.lfp");
  EXPECT_TRUE(f01.Toc("f01").Json("f01").contains("picture"));
}

TEST(LfpContainerWriter, RoundTripKeepsOrderKindsPayloadsAndVerifiesEverySha1) {
  const LfpContainer original = SyntheticContainer();
  const std::vector<std::uint8_t> bytes = SerializeLfpContainer(original);
  // Header (16) + per section 96 + payload, each padded to 16.
  std::size_t expected = 16;
  for (const auto& s : original.sections) expected += (96 + s.payload.size() + 15) / 16 * 16;
  EXPECT_EQ(bytes.size(), expected);
  EXPECT_EQ(BigEndianAt(bytes, 16 + 12), 100'003u);  // first section's big-endian length

  const LfpContainer parsed = ParseLfpContainer(bytes, "synthetic");
  ASSERT_EQ(parsed.sections.size(), original.sections.size());
  for (std::size_t i = 0; i < parsed.sections.size(); ++i) {
    EXPECT_EQ(parsed.sections[i].kind, original.sections[i].kind);
    EXPECT_EQ(parsed.sections[i].payload, original.sections[i].payload);
    EXPECT_EQ(parsed.sections[i].sha1, original.sections[i].sha1);
    EXPECT_EQ(parsed.sections[i].offset % 16, 0u);
  }
  EXPECT_EQ(parsed.FindToc(), &parsed.sections.back());  // LFM last, found by magic
  const nlohmann::json toc = parsed.Toc("synthetic").Json("synthetic");
  const LfpSection& raw = parsed.Resolve(toc["frames"][0]["frame"]["imageRef"].get<std::string>(), "s", "imageRef");
  EXPECT_EQ(raw.payload, RandomBytes(100'003, 1));
}

TEST(LfpContainerWriter, WritesAtomicallyAndReadsBack) {
  TempDir dir;
  const LfpContainer original = SyntheticContainer();
  WriteLfpContainer(original, dir / "capture.lfr");
  const LfpContainer back = ReadLfpContainer(dir / "capture.lfr");
  ASSERT_EQ(back.sections.size(), original.sections.size());
  EXPECT_EQ(back.sections[0].payload, original.sections[0].payload);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);  // no temporary left behind
}

TEST(LfpContainerWriter, StaleSha1InTheModelIsRecomputed) {
  LfpContainer c = SyntheticContainer();
  c.sections[0].payload[0] ^= 0xFF;  // edited after AddBinary
  const LfpContainer parsed = ParseLfpContainer(SerializeLfpContainer(c), "edited");
  EXPECT_EQ(parsed.sections[0].sha1, Sha1Reference(c.sections[0].payload));
}

TEST(LfpContainerBadInput, TruncatedFile) {
  const std::vector<std::uint8_t> good = SerializeLfpContainer(SyntheticContainer());
  EXPECT_NE(ErrorOf([&] { ParseLfpContainer(std::span(good).first(10), "cut.lfp"); }).find("truncated LFP file"),
            std::string::npos);
  // Cut inside the first section's header and inside its payload.
  for (const std::size_t cut : {std::size_t{16 + 40}, std::size_t{16 + 96 + 5000}, good.size() - 30}) {
    const std::string message = ErrorOf([&] { ParseLfpContainer(std::span(good).first(cut), "cut.lfp"); });
    EXPECT_NE(message.find("cut.lfp: section"), std::string::npos) << message;
    EXPECT_TRUE(message.find("truncated") != std::string::npos || message.find("past the end") != std::string::npos)
        << message;
  }
}

TEST(LfpContainerBadInput, WrongFileMagic) {
  std::vector<std::uint8_t> bytes = SerializeLfpContainer(SyntheticContainer());
  bytes[1] = 'X';
  const std::string message = ErrorOf([&] { ParseLfpContainer(bytes, "bad.lfp"); });
  EXPECT_NE(message.find("bad.lfp: wrong file magic"), std::string::npos) << message;
  EXPECT_FALSE(HasLfpMagic(bytes));
}

TEST(LfpContainerBadInput, WrongSectionMagicNamesTheSection) {
  std::vector<std::uint8_t> bytes = SerializeLfpContainer(SyntheticContainer());
  const std::size_t second = 16 + (96 + 100'003 + 15) / 16 * 16;
  bytes[second + 3] = 'Q';  // LFC -> LFQ
  const std::string message = ErrorOf([&] { ParseLfpContainer(bytes, "bad.lfp"); });
  EXPECT_NE(message.find("section 1 at byte offset " + std::to_string(second)), std::string::npos) << message;
  EXPECT_NE(message.find("wrong section magic"), std::string::npos) << message;
}

TEST(LfpContainerBadInput, LengthPastTheEnd) {
  std::vector<std::uint8_t> bytes = SerializeLfpContainer(SyntheticContainer());
  bytes[16 + 12] = 0x7F;  // first section claims ~2 GB
  const std::string message = ErrorOf([&] { ParseLfpContainer(bytes, "long.lfp"); });
  EXPECT_NE(message.find("section 0 at byte offset 16"), std::string::npos) << message;
  EXPECT_NE(message.find("past the end"), std::string::npos) << message;
}

TEST(LfpContainerBadInput, Sha1MismatchNamesSectionAndOffset) {
  std::vector<std::uint8_t> bytes = SerializeLfpContainer(SyntheticContainer());
  bytes[16 + 96 + 500] ^= 1;  // one bit of the first payload
  const std::string message = ErrorOf([&] { ParseLfpContainer(bytes, "flip.lfr"); });
  EXPECT_NE(message.find("flip.lfr: section 0 at byte offset 16: SHA-1 mismatch"), std::string::npos) << message;
}

TEST(LfpContainerBadInput, MalformedSha1Field) {
  std::vector<std::uint8_t> bytes = SerializeLfpContainer(SyntheticContainer());
  bytes[16 + 16] = 'S';  // "Sha1-"
  EXPECT_NE(ErrorOf([&] { ParseLfpContainer(bytes, "x"); }).find("malformed SHA-1"), std::string::npos);
}

TEST(LfpContainerBadInput, NoSectionsMissingTocAndDanglingReference) {
  LfpContainer empty;
  EXPECT_NE(ErrorOf([&] { ParseLfpContainer(SerializeLfpContainer(empty), "e"); }).find("no sections"),
            std::string::npos);
  LfpContainer no_toc;
  no_toc.AddBinary({1, 2, 3});
  EXPECT_NE(ErrorOf([&] { no_toc.Toc("n.lfp"); }).find("n.lfp: no LFM"), std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              no_toc.Resolve("sha1-0000", "n.lfp", "frames[0].frame.imageRef");
            }).find("frames[0].frame.imageRef refers to sha1-0000"),
            std::string::npos);
}

TEST(LfpContainerBadInput, InvalidJsonInASectionIsAnError) {
  LfpContainer c;
  const std::string text = "{\"a\": [1, 2";
  c.AddBinary(std::vector<std::uint8_t>(text.begin(), text.end()), SectionKind::kMetadata);
  const LfpContainer parsed = ParseLfpContainer(SerializeLfpContainer(c), "j.lfp");
  EXPECT_NE(ErrorOf([&] { parsed.Toc("j.lfp").Json("j.lfp"); }).find("j.lfp"), std::string::npos);
}

TEST(LfpContainerBadInput, MissingFileAndFolder) {
  TempDir dir;
  EXPECT_NE(ErrorOf([&] { ReadLfpContainer(dir / "nope.lfp"); }).find("no such file"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ReadLfpContainer(dir.path()); }).find("not a regular file"), std::string::npos);
}

}  // namespace
}  // namespace lfsp::decode
