// The bundled simulator samples (samples/*/capture.* + whites/) read back through the decode file-format layer:
// every SHA-1 verified, raw image present and of the size the metadata states, white images indexed and the one
// for the capture's serial/zoom/focus chosen. This ties the simulator's writers to the reader in both schemas.

#include <gtest/gtest.h>

#include "lfsp/decode/lytro_capture.h"
#include "lfsp/decode/white_database.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> SampleCaptures() {
  std::vector<fs::path> captures;
  const fs::path samples = lfsp::testing::SourceDir() / "samples";
  std::error_code ec;
  for (const auto& dir : fs::directory_iterator(samples, ec)) {
    for (const char* name : {"capture.LFR", "capture.lfp"}) {
      if (fs::is_regular_file(dir.path() / name)) captures.push_back(dir.path() / name);
    }
  }
  std::sort(captures.begin(), captures.end());
  return captures;
}

TEST(Samples, CapturesAndWhiteImagesReadBack) {
  const auto captures = SampleCaptures();
  if (captures.empty()) GTEST_SKIP() << "no samples/*/capture.* yet (made by lfsp simulate)";
  for (const fs::path& path : captures) {
    SCOPED_TRACE(path.string());
    const LytroCapture capture = OpenLytroCapture(path);
    ASSERT_TRUE(capture.metadata.has_value()) << capture.metadata_problem;
    ASSERT_TRUE(capture.HasRawImage());
    EXPECT_FALSE(capture.IsWhiteImage());
    EXPECT_TRUE(capture.UnreferencedSections().empty());
    const RawFormat& format = capture.metadata->RequireRawFormat();
    const RawImage raw = capture.ReadRawImage();
    EXPECT_EQ(raw.width, format.width);
    EXPECT_EQ(raw.height, format.height);
    const bool f01 = path.extension() == ".lfp";
    EXPECT_EQ(format.packing, f01 ? RawPacking::kBits12BigEndian : RawPacking::kBits10Illum);
    EXPECT_EQ(format.mosaic, f01 ? BayerPattern::kBGGR : BayerPattern::kGRBG);
    const auto [lowest, highest] = std::minmax_element(raw.pixels.begin(), raw.pixels.end());
    EXPECT_LE(*highest, format.white.gr);
    EXPECT_LT(*lowest, *highest);  // an image, not a constant

    const fs::path whites = path.parent_path() / "whites";
    ASSERT_TRUE(fs::is_directory(whites)) << whites;                // both bundled samples ship their white images
    const WhiteImageDatabase db = BuildWhiteImageDatabase(whites);  // reads only; writes nothing into samples/
    EXPECT_TRUE(db.skipped.empty()) << db.skipped.front();
    const WhiteImageChoice choice = SelectWhiteImage(db, *capture.metadata);
    EXPECT_EQ(choice.entry->serial, capture.metadata->serial);
    EXPECT_EQ(choice.entry->width, format.width);
    EXPECT_FALSE(choice.entry->dark);
  }
}

}  // namespace
}  // namespace lfsp::decode
