// Issue 49: a simulated F01 capture whose mosaic is stored the way the real F01 frames of ../shared/data/lytro_raw
// were (dark, raw codes scaled to 8 bits, greyscale JPEG at quality 75), decoded with and without the JPEG
// restoration, against the scene's ground truth and against the same 8-bit mosaic stored losslessly.

#include <gtest/gtest.h>

#include "lfsp/core/load.h"
#include "lfsp/decode/view_quality.h"
#include "test_support.h"

namespace lfsp {
namespace {

using lfsp::testing::RunLfsp;
using lfsp::testing::TempDir;

struct Decoded {
  decode::CentreFidelity fidelity;
  double bands = 0.0;
};

Decoded DecodeAndScore(const std::filesystem::path& mosaic, const std::filesystem::path& out, const LightField& truth,
                       const std::string& restore_iterations) {
  const auto result = RunLfsp({"-q", "decode", mosaic.string(), "--camera", "f01", "--colour", "linear",
                               "--jpeg-restore", restore_iterations, "--out", out.string()});
  EXPECT_EQ(result.exit_status, 0) << result.err;
  const LightField decoded = LoadLightField(out).light_field;
  return {decode::CompareCentreWithTruth(decoded, truth), decode::ChromaBandRatio(decoded, decoded.shape().Centre())};
}

TEST(JpegCapture, RestorationRecoversPartOfWhatTheJpegTookAndAddsNoBands) {
  TempDir dir;
  // Exposure 0.3: the mosaic's median code is about 20 of 255 (the real frames: 25-42), so that the JPEG zeroes most
  // colour coefficients as it does in them. A brightly scaled mosaic keeps its colour and shows no bands.
  const auto simulated = RunLfsp({"-q", "simulate", "--camera", "f01", "--scene", "two-horses", "--exposure", "0.3",
                                  "--mosaic-jpeg", "75", "--no-white-images", "--out", (dir / "sim").string()});
  ASSERT_EQ(simulated.exit_status, 0) << simulated.err;
  const LightField truth = LoadLightField(dir / "sim" / "ground_truth" / "decoded.h5").light_field;
  const Decoded lossless = DecodeAndScore(dir / "sim" / "capture_mosaic.png", dir / "png.h5", truth, "0");
  const Decoded plain = DecodeAndScore(dir / "sim" / "capture_mosaic.jpg", dir / "plain.h5", truth, "0");
  const Decoded restored = DecodeAndScore(dir / "sim" / "capture_mosaic.jpg", dir / "restored.h5", truth, "30");
  for (const auto& [name, d] : {std::pair{"lossless", lossless}, {"plain", plain}, {"restored", restored}}) {
    RecordProperty(std::string(name) + "_psnr_db", std::to_string(d.fidelity.psnr_db));
    RecordProperty(std::string(name) + "_chroma_error", std::to_string(d.fidelity.chroma_error));
    RecordProperty(std::string(name) + "_bands", std::to_string(d.bands));
  }
  // Measured: lossless 35.6 dB, chroma error 0.016, bands 4.0; plain JPEG 24.9 dB, 0.045, 2.4; restored 26.0 dB,
  // 0.041, 3.1. Most of the loss is colour the quantization zeroed in whole blocks, which no decoder can get back;
  // issue 49's 2.5 dB is far from what this exposure allows (see BENCHMARKS.md).
  EXPECT_GT(lossless.fidelity.psnr_db, 33.0);
  EXPECT_GT(restored.fidelity.psnr_db, plain.fidelity.psnr_db + 0.7);
  EXPECT_LT(restored.fidelity.chroma_error, 0.95 * plain.fidelity.chroma_error);
  EXPECT_LE(restored.bands, lossless.bands + 0.5);
}

}  // namespace
}  // namespace lfsp
