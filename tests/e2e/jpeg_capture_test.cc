// Issue 49: a simulated F01 capture whose mosaic is stored the way the real F01 frames of ../shared/data/lytro_raw
// were (dark, raw codes scaled to 8 bits, greyscale JPEG at quality 75), decoded with and without the JPEG
// restoration, against the scene's ground truth and against the same 8-bit mosaic stored losslessly.

#include <gtest/gtest.h>

#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/decode/jpeg_block_gain.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/view_quality.h"
#include "test_support.h"

namespace lfsp {
namespace {

using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

struct Decoded {
  decode::CentreFidelity fidelity;
  double bands = 0.0;         // ChromaBandRatio of the centre view as stored (16-bit: negative noise clipped)
  double signed_bands = 0.0;  // the same before storage, as the summary's decode.centre_bands.chroma
  double block_rows = 0.0;    // BlockRowLuminance of the centre view, % of the local level
};

Decoded DecodeAndScore(const std::filesystem::path& mosaic, const std::filesystem::path& out, const LightField& truth,
                       const std::string& restore_iterations) {
  const auto result = RunLfsp({"-q", "decode", mosaic.string(), "--camera", "f01", "--colour", "linear",
                               "--jpeg-restore", restore_iterations, "--out", out.string()});
  EXPECT_EQ(result.exit_status, 0) << result.err;
  const LightField decoded = LoadLightField(out).light_field;
  const nlohmann::json summary = lfsp::testing::LoadJson(out.parent_path() / (out.stem().string() + ".summary.json"));
  return {decode::CompareCentreWithTruth(decoded, truth), decode::ChromaBandRatio(decoded, decoded.shape().Centre()),
          summary["decode"]["centre_bands"]["chroma"].get<double>(),
          decode::BlockRowLuminance(decoded, decoded.shape().Centre(),
                                    decode::LensletGrid::FromJson(summary["grid"], out.string()),
                                    decoded.metadata["decode"]["view_step_pixels"])};
}

struct ThreeDecodes {
  Decoded lossless;  // the 8-bit mosaic stored as PNG
  Decoded plain;     // its JPEG, decoded the plain way
  Decoded restored;  // its JPEG with the restoration (30 rounds)
};

// Simulates `scene` as an F01 capture whose mosaic is also written as the real frames were (8 bits, quality 75), then
// decodes it three ways against the truth and records every figure.
ThreeDecodes SimulateAndDecode(const TempDir& dir, const std::string& scene, const std::string& exposure) {
  const auto simulated = RunLfsp({"-q", "simulate", "--camera", "f01", "--scene", scene, "--exposure", exposure,
                                  "--mosaic-jpeg", "75", "--no-white-images", "--out", (dir / "sim").string()});
  if (simulated.exit_status != 0) throw Error("lfsp simulate --scene " + scene + " failed: " + simulated.err);
  const LightField truth = LoadLightField(dir / "sim" / "ground_truth" / "decoded.h5").light_field;
  const ThreeDecodes decodes{DecodeAndScore(dir / "sim" / "capture_mosaic.png", dir / "png.h5", truth, "0"),
                             DecodeAndScore(dir / "sim" / "capture_mosaic.jpg", dir / "plain.h5", truth, "0"),
                             DecodeAndScore(dir / "sim" / "capture_mosaic.jpg", dir / "restored.h5", truth, "30")};
  for (const auto& [name, d] :
       {std::pair{"lossless", decodes.lossless}, {"plain", decodes.plain}, {"restored", decodes.restored}}) {
    ::testing::Test::RecordProperty(std::string(name) + "_psnr_db", std::to_string(d.fidelity.psnr_db));
    ::testing::Test::RecordProperty(std::string(name) + "_chroma_error", std::to_string(d.fidelity.chroma_error));
    ::testing::Test::RecordProperty(std::string(name) + "_bands", std::to_string(d.bands));
    ::testing::Test::RecordProperty(std::string(name) + "_signed_bands", std::to_string(d.signed_bands));
    ::testing::Test::RecordProperty(std::string(name) + "_block_rows_percent", std::to_string(d.block_rows));
  }
  return decodes;
}

TEST(JpegCapture, RestorationRecoversPartOfWhatTheJpegTookAndAddsNoBands) {
  TempDir dir;
  // Exposure 0.3: the mosaic's median code is about 20 of 255 (the real frames: 25-42), so that the JPEG zeroes most
  // colour coefficients as it does in them. A brightly scaled mosaic keeps its colour and shows no bands.
  const auto [lossless, plain, restored] = SimulateAndDecode(dir, "two-horses", "0.3");
  // Measured: lossless 35.6 dB, chroma error 0.016, bands 4.0; plain JPEG 25.0 dB, 0.0453, 2.5; restored 26.10 dB,
  // 0.0424 (1.4 % under the 0.95 x plain asserted), 3.2 (26.11 dB, 0.040, 3.4 while the prior's narrow filter let 2.9 %
  // of the luminance through as colour a round, which shrank every carrier's colour towards grey, the guessed colour of
  // zeroed blocks too). Most of the loss is colour the quantization zeroed in whole blocks, which no decoder can get
  // back; issue 49's 2.5 dB is far from what this exposure allows (see BENCHMARKS.md).
  EXPECT_GT(lossless.fidelity.psnr_db, 33.0);
  EXPECT_GT(restored.fidelity.psnr_db, plain.fidelity.psnr_db + 0.7);
  EXPECT_LT(restored.fidelity.chroma_error, 0.95 * plain.fidelity.chroma_error);
  EXPECT_LE(restored.bands, lossless.bands + 0.5);
  // The gain each view takes from where its samples fall down the JPEG's blocks is divided out (jpeg_block_gain.h):
  // the centre view's luminance that follows the blocks' rows read 3.3 % of the local level (plain and restored)
  // before, 0.36 % (plain) and 0.14 % (restored) after; the lossless mosaic's decode reads 0.08 %. The restored
  // decode reads 0.03 % since the prior leaves the luminance alone.
  EXPECT_LT(lossless.block_rows, 0.15);
  EXPECT_LT(restored.block_rows, 0.1);
  EXPECT_LT(plain.block_rows, 0.6);
}

// The simulator's `leaves` scene writes what two-horses does not: the real frames' bands. Its large smooth green
// leaves sit, in a bluish light, where the JPEG keeps the (7,7) coefficient in some blocks and not in others, so the
// blocks' beat against the lens rows stripes the colour as on the real IMG_3 (issue 49, item 1). The bands are in
// the JPEG, not in the scene or the decoder: the lossless 8-bit mosaic decodes without them.
TEST(JpegCapture, LeavesInShadeShowTheRealFramesBands) {
  TempDir dir;
  const auto [lossless, plain, restored] = SimulateAndDecode(dir, "leaves", "1.8");
  // Measured: lossless 46.3 dB, chroma error 0.0031, bands 1.86; plain JPEG 31.6 dB, 0.024, 5.7; restored 31.55 dB,
  // 0.025, 1.93. The restored decode read 31.0 dB and 5.8 while the prior's narrow filter let the luminance through
  // as colour (2.9 % a round: the mosaic came out 1.25 codes darker than its truth, every block's mean at the low
  // edge of its DC bin), and 31.2 dB and 11.9 before the restoration ended on its prior. The real IMG_3 reads 11.5
  // plain; what it reads restored is its leaves' veins (real_raw_test.cc). Asserted: what makes the scene worth having
  // (the JPEG, not the scene, makes the bands), and issue 49's band target for the restored decode: at most the
  // lossless decode's plus 0.5, on the views as stored (16-bit: the dark ground's negative noise clipped; before
  // storage the restored views read 2.56 against 1.88, BENCHMARKS.md). Its 2.5 dB target is not met: the colour the
  // JPEG zeroed is lost.
  EXPECT_GT(lossless.fidelity.psnr_db, 40.0);
  EXPECT_LT(lossless.bands, 3.0);
  EXPECT_GT(plain.bands, lossless.bands + 2.5);
  EXPECT_LE(restored.bands, lossless.bands + 0.5);
  // Before storage the restored views read 2.56 against the plain decode's 5.67 (the prior's leak: 5.88): the band is
  // gone there too, not only clipped away, although 0.68 above the lossless 1.88 remains.
  EXPECT_LT(restored.signed_bands, 0.5 * plain.signed_bands);
  EXPECT_GT(restored.fidelity.psnr_db, plain.fidelity.psnr_db - 0.3);
}

}  // namespace
}  // namespace lfsp
