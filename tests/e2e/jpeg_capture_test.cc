// Issue 49: a simulated F01 capture whose mosaic is stored the way the real F01 frames of ../shared/data/lytro_raw
// were (dark, raw codes scaled to 8 bits, greyscale JPEG at quality 75), decoded with and without the JPEG
// restoration, against the scene's ground truth and against the same 8-bit mosaic stored losslessly; and a mosaic of
// other colours that stores the very same JPEG, which no decoder can tell from the capture.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lfsp/core/error.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/load.h"
#include "lfsp/decode/jpeg_block_gain.h"
#include "lfsp/decode/jpeg_mosaic.h"
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

// `lfsp decode MOSAIC --camera f01 --colour linear` into `out` (restore_iterations: `--jpeg-restore`, for JPEGs).
LightField DecodeF01(const std::filesystem::path& mosaic, const std::filesystem::path& out,
                     const std::string& restore_iterations = "30") {
  const auto result = RunLfsp({"-q", "decode", mosaic.string(), "--camera", "f01", "--colour", "linear",
                               "--jpeg-restore", restore_iterations, "--out", out.string()});
  EXPECT_EQ(result.exit_status, 0) << result.err;
  return LoadLightField(out).light_field;
}

Decoded DecodeAndScore(const std::filesystem::path& mosaic, const std::filesystem::path& out, const LightField& truth,
                       const std::string& restore_iterations) {
  const LightField decoded = DecodeF01(mosaic, out, restore_iterations);
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

// Simulates `scene` as an F01 capture in dir/sim whose mosaic is also written as the real frames were (8 bits,
// quality 75: capture_mosaic.jpg; losslessly: capture_mosaic.png), and returns its ideal light field.
LightField Simulate(const TempDir& dir, const std::string& scene, const std::string& exposure) {
  const auto simulated = RunLfsp({"-q", "simulate", "--camera", "f01", "--scene", scene, "--exposure", exposure,
                                  "--mosaic-jpeg", "75", "--no-white-images", "--out", (dir / "sim").string()});
  if (simulated.exit_status != 0) throw Error("lfsp simulate --scene " + scene + " failed: " + simulated.err);
  return LoadLightField(dir / "sim" / "ground_truth" / "decoded.h5").light_field;
}

// Simulates `scene` (Simulate), then decodes it three ways against the truth and records every figure.
ThreeDecodes SimulateAndDecode(const TempDir& dir, const std::string& scene, const std::string& exposure) {
  const LightField truth = Simulate(dir, scene, exposure);
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
  // back from the data (OneJpegHoldsACaptureOfOtherColours: here the complement without smoothing, which stores the
  // same file, bounds any decoder at 31.96 dB on one of the two against the target's 33.05; smoothed, 33.75).
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

// Blocks of `mosaic` (8-bit codes) that an encoder at quality 75 stores otherwise than `stored`: written and read back.
std::vector<cv::Rect> BlocksStoredOtherwise(const cv::Mat& mosaic, const decode::JpegCoefficients& stored,
                                            const std::filesystem::path& scratch) {
  cv::Mat bytes;
  mosaic.convertTo(bytes, CV_8UC1);
  WriteImage(bytes, scratch, 8, {{"Compression", "jpeg:75"}});
  const decode::JpegCoefficients written = decode::ReadJpegCoefficients(scratch).value();
  EXPECT_EQ(written.quant, stored.quant);  // the same table, or the same indices would not be the same file
  std::vector<cv::Rect> differing;
  for (int by = 0; by < stored.blocks_y; ++by)
    for (int bx = 0; bx < stored.blocks_x; ++bx)
      if (!stored.SameBlock(written, bx, by)) differing.emplace_back(bx * 8, by * 8, 8, 8);
  return differing;
}

// The least error, in the centre view, that one decoded picture can have against both `a` and `b` at once, with
// per-channel gains fitted to each as CompareCentreWithTruth fits them: rms over the samples of the larger of the
// two errors is at least this. With gains free, a channel of the picture is a direction; its errors against a's and
// b's channel are |a| sin(x) and |b| sin(t - x), t the angle between those two, and the least sum of their squares
// over x is (|a|^2 + |b|^2 - sqrt(|a|^4 + |b|^4 + 2 |a|^2 |b|^2 cos 2t)) / 2; the larger error is at least half the
// sum. Both views in the same units, `border` pixels left out as CompareCentreWithTruth leaves them.
double LeastErrorAgainstBoth(const cv::Mat& a, const cv::Mat& b, int border = 8) {
  const cv::Rect inside(border, border, a.cols - 2 * border, a.rows - 2 * border);
  double least = 0.0;
  for (int c = 0; c < 3; ++c) {
    cv::Mat ac, bc;
    cv::extractChannel(a(inside), ac, c);
    cv::extractChannel(b(inside), bc, c);
    const double aa = ac.dot(ac), bb = bc.dot(bc), ab = ac.dot(bc);
    const double cos_2t = 2.0 * ab * ab / (aa * bb) - 1.0;
    least += 0.5 * (aa + bb - std::sqrt(aa * aa + bb * bb + 2.0 * aa * bb * cos_2t));
  }
  return std::sqrt(0.5 * least / (3.0 * static_cast<double>(inside.area())));
}

// Issue 49, item 1 asks the restored decode to come within 2.5 dB of the lossless one: how much of that colour does
// the file hold? On the leaves capture (the one whose JPEG damage is the real frames', bands included) a second 8-bit
// mosaic, the complementary colour run through the restoration's rounds, stores the very same coefficients, so a
// decoder makes one picture of both. Measured as the issue measures (gains fitted per channel), that picture reads on
// one of the two at most 38.51 dB against the truth, where the target asks 43.77 dB of both, if the other mosaic is
// as near its own truth as the capture's lossless decode is to its. That holds against a decoder that goes by the
// data and smooth colour; it does not rule out one that finds colour without bands inside the bins, since the other
// mosaic has bands (15.5 on the measure, the capture 1.86) as everything moved into the bins here has (BENCHMARKS.md,
// forty-first session).
TEST(JpegCapture, OneJpegHoldsACaptureOfOtherColours) {
  TempDir dir;
  const LightField truth = Simulate(dir, "leaves", "1.8");
  const cv::Mat original = ReadImage(dir / "sim" / "capture_mosaic.png").pixels * 255.0;  // CV_32FC1, 8-bit codes
  const decode::JpegCoefficients stored = decode::ReadJpegCoefficients(dir / "sim" / "capture_mosaic.jpg").value();
  ASSERT_EQ(original.cols, stored.blocks_x * 8);
  ASSERT_EQ(original.rows, stored.blocks_y * 8);
  // The complement: the binomial 3 x 3 mean has no response at any Bayer carrier, so 2 x mean - mosaic flips every
  // carrier's sign. It flips the finest luminance detail too (its response is 2 H - 1); the bins put that back. The
  // restoration's rounds, started there, smooth those colours near the file's bins; moved into the bins below, the
  // mosaic carries the blocks' bands again (recorded below), if fainter than without the rounds.
  const cv::Mat binomial = (cv::Mat_<float>(3, 1) << 0.25f, 0.5f, 0.25f);
  cv::Mat mean;
  cv::sepFilter2D(original, mean, CV_32F, binomial, binomial, cv::Point(-1, -1), 0, cv::BORDER_REFLECT);
  decode::MosaicRestoreOptions from_complement;
  from_complement.start = 2.0 * mean - original;
  cv::Mat other = decode::RestoreJpegMosaic(stored, from_complement);
  // Into the file's bins, with room for the rounding to codes (ProjectOntoJpegBins).
  for (int round = 0; round < 20; ++round) {
    decode::ProjectOntoJpegBins(stored, other, 0.6);
    other.convertTo(other, CV_8UC1);  // rounds and saturates
    other.convertTo(other, CV_32FC1);
  }
  // Where the encoder's integer DCT still rounds a coefficient into another bin, the block keeps the capture's codes.
  // A greyscale JPEG's blocks are coded apart, so once is enough.
  const std::vector<cv::Rect> differing = BlocksStoredOtherwise(other, stored, dir / "other.jpg");
  for (const cv::Rect& block : differing) original(block).copyTo(other(block));
  RecordProperty("blocks_reverted", std::to_string(differing.size()));
  ASSERT_TRUE(BlocksStoredOtherwise(other, stored, dir / "other.jpg").empty());
  cv::Mat changed;
  cv::absdiff(other, original, changed);
  // INTER_AREA at the integer factor 8 is each block's mean: nonzero where any of its codes changed.
  cv::resize(changed, changed, cv::Size(stored.blocks_x, stored.blocks_y), 0, 0, cv::INTER_AREA);
  const double changed_block_share = cv::countNonZero(changed) / static_cast<double>(changed.total());
  RecordProperty("changed_block_share", std::to_string(changed_block_share));
  EXPECT_GT(changed_block_share, 0.99);  // measured 0.9998 (the 34 blocks reverted)
  cv::Mat other_bytes;
  other.convertTo(other_bytes, CV_8UC1);
  WriteImage(other_bytes, dir / "other.png", 8);

  // Both decoded losslessly, in the truth's units (the capture's gains against the truth, for both: one camera).
  LightField capture = DecodeF01(dir / "sim" / "capture_mosaic.png", dir / "capture.h5");
  LightField other_decode = DecodeF01(dir / "other.png", dir / "other.h5");
  const decode::CentreFidelity lossless = decode::CompareCentreWithTruth(capture, truth);
  // Recorded, not asserted: moving a mosaic into the bins puts the blocks' pattern back, whatever its colour (the
  // restoration's own output so moved reads 6.1; the complement without the rounds 17.2).
  RecordProperty("other_bands", std::to_string(decode::ChromaBandRatio(other_decode, other_decode.shape().Centre())));
  RecordProperty("capture_bands", std::to_string(decode::ChromaBandRatio(capture, capture.shape().Centre())));
  const cv::Scalar gains(lossless.gains[0], lossless.gains[1], lossless.gains[2]);
  cv::Mat capture_centre = capture.View(capture.shape().Centre()),
          other_centre = other_decode.View(capture.shape().Centre());
  cv::multiply(capture_centre, gains, capture_centre);
  cv::multiply(other_centre, gains, other_centre);
  const double apart_db = decode::CompareCentreWithTruth(other_decode, capture).psnr_db;
  const auto rms_of_db = [](double db) { return std::pow(10.0, -db / 20.0); };
  const double least = LeastErrorAgainstBoth(capture_centre, other_centre) - rms_of_db(lossless.psnr_db);
  const double best_on_both_db = -20.0 * std::log10(least);
  RecordProperty("capture_lossless_psnr_db", std::to_string(lossless.psnr_db));
  RecordProperty("other_vs_capture_psnr_db", std::to_string(apart_db));
  RecordProperty("best_on_both_psnr_db", std::to_string(best_on_both_db));
  // Measured 46.27 dB; the two lossless decodes 30.23 dB apart (gains fitted): the colour flipped (the restoration's
  // own output moved into the bins the same way lies 32.31 dB off and bounds at 41.90); one picture of both at most
  // 38.51 dB from one of the truths, where the target asks lossless - 2.5 = 43.77 dB.
  EXPECT_GT(lossless.psnr_db, 40.0);
  EXPECT_LT(apart_db, 31.0);
  ASSERT_GT(least, 0.0);
  EXPECT_LT(best_on_both_db, lossless.psnr_db - 2.5);
}

}  // namespace
}  // namespace lfsp
