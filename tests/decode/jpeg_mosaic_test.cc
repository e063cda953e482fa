// Greyscale JPEG mosaics (issue 49): the coefficients are read as stored, and the restoration brings back the Bayer
// colour that quantization took from a faint, lenslet-like mosaic, without the block pattern.

#include "lfsp/decode/jpeg_mosaic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "lfsp/core/image_io.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

using lfsp::testing::ErrorOf;
using lfsp::testing::TempDir;

constexpr int kSize = 512;
constexpr double kLensRow = 8.6;  // an F01's lens rows; lens columns 9.93 px
constexpr double kLensColumn = 9.93;

// The true mosaic, in 8-bit codes: a dark lenslet image (micro-images brightest at their centres over a black level
// of 10.5, as the real F01 frames are) of a green surface whose colour changes slowly across the frame. BGGR: green
// sits 3 codes (at a micro-image centre) above red and blue, red and blue differ by up to 1.5 codes. Without
// `coloured`, a grey surface: every pixel of a micro-image at `level` above black.
struct FaintLensletMosaic {
  cv::Mat codes = cv::Mat(kSize, kSize, CV_32FC1);
  explicit FaintLensletMosaic(bool coloured = true, double level = 14.0) {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const double row = y / kLensRow, column = x / kLensColumn - 0.5 * (static_cast<int>(std::floor(row)) & 1);
        const double dy = row - std::floor(row) - 0.5, dx = column - std::floor(column) - 0.5;
        // A flat-topped micro-image, as the simulator's and real F01 ones are: full inside 0.35 of the pitch,
        // falling smoothly to 0 at 0.55.
        const double radius = std::sqrt(dx * dx + dy * dy);
        const double profile =
            radius < 0.35 ? 1.0 : (radius > 0.55 ? 0.0 : 0.5 + 0.5 * std::cos(M_PI * (radius - 0.35) / 0.2));
        const double green_excess = 10.0 * (0.8 + 0.4 * x / kSize), red_minus_blue = 4.0 * y / kSize;
        const bool green = ((x + y) & 1) == 1, blue = !green && (y & 1) == 0;
        double signal = level;
        if (coloured) signal += green ? green_excess : (blue ? -0.5 : 0.5) * red_minus_blue;
        codes.at<float>(y, x) = static_cast<float>(10.5 + profile * signal);
      }
  }
};

// How much the error of one carrier's colour (the mosaic times the carrier's sign) depends on the row inside the
// JPEG block: its mean over each of the 8 rows of every block, largest minus smallest. This block envelope is what
// lens rows 8.6 px apart turn into colour bands; a decoder cannot see it as anything but the scene.
double BlockEnvelope(const cv::Mat& estimate, const cv::Mat& truth, int carrier) {
  double sums[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const int parity = carrier == 0 ? x + y : (carrier == 1 ? x : y);
      sums[y % 8] += ((parity & 1) ? -1.0 : 1.0) * (estimate.at<float>(y, x) - truth.at<float>(y, x));
    }
  double low = sums[0], high = sums[0];
  for (double sum : sums) {
    low = std::min(low, sum);
    high = std::max(high, sum);
  }
  return (high - low) / (kSize * kSize / 8.0);
}

cv::Mat AsBytes(const cv::Mat& codes) {
  cv::Mat bytes;
  codes.convertTo(bytes, CV_8UC1);  // rounds and saturates
  return bytes;
}

TEST(JpegMosaic, CoefficientsAreReadAsStoredWithTheStandardQuality75Table) {
  TempDir dir;
  const FaintLensletMosaic mosaic;
  WriteImage(AsBytes(mosaic.codes), dir / "mosaic.jpg", 8, {{"Compression", "jpeg:75"}});
  const std::optional<JpegCoefficients> coefficients = ReadJpegCoefficients(dir / "mosaic.jpg");
  ASSERT_TRUE(coefficients);
  EXPECT_EQ(coefficients->width, kSize);
  EXPECT_EQ(coefficients->blocks_x, kSize / 8);
  // libjpeg's luminance table at quality 75: the real F01 frames carry the same (first row 8 6 5 8 12 20 26 31).
  const float first_row[8] = {8, 6, 5, 8, 12, 20, 26, 31};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(coefficients->quant[static_cast<std::size_t>(k)], first_row[k]);
  // Without iterations the restoration is the plain decode, within libjpeg's integer IDCT rounding.
  MosaicRestoreOptions plain;
  plain.iterations = 0;
  const cv::Mat ours = RestoreJpegMosaic(*coefficients, plain);
  const cv::Mat libjpeg = ReadImage(dir / "mosaic.jpg").pixels * 255.0;
  EXPECT_LE(cv::norm(ours, libjpeg, cv::NORM_INF), 1.01);
}

TEST(JpegMosaic, RestorationBringsBackTheColourQuantizationTook) {
  TempDir dir;
  const FaintLensletMosaic mosaic;
  WriteImage(AsBytes(mosaic.codes), dir / "mosaic.jpg", 8, {{"Compression", "jpeg:75"}});
  const JpegCoefficients coefficients = *ReadJpegCoefficients(dir / "mosaic.jpg");
  MosaicRestoreOptions plain;
  plain.iterations = 0;
  const cv::Mat decoded = RestoreJpegMosaic(coefficients, plain);
  MosaicRestoreReport report;
  const cv::Mat restored = RestoreJpegMosaic(coefficients, {}, &report);
  EXPECT_EQ(report.iterations, MosaicRestoreOptions{}.iterations);
  EXPECT_GT(report.mean_change, 0.0);
  // Green against red and blue (the carrier most blocks keep only as the (7,7) coefficient, or lose).
  const double plain_green = BlockEnvelope(decoded, mosaic.codes, 0);
  const double restored_green = BlockEnvelope(restored, mosaic.codes, 0);
  RecordProperty("green_envelope_plain", std::to_string(plain_green));
  RecordProperty("green_envelope_restored", std::to_string(restored_green));
  // Measured 1.74 -> 0.50 codes.
  EXPECT_LT(restored_green, 0.5 * plain_green);
  // And it stays closer to the true mosaic than the plain decode (the quantization bins allow the truth; the prior
  // must not pull far from it).
  const double plain_rms = cv::norm(decoded, mosaic.codes, cv::NORM_L2) / std::sqrt(double(kSize) * kSize);
  const double restored_rms = cv::norm(restored, mosaic.codes, cv::NORM_L2) / std::sqrt(double(kSize) * kSize);
  RecordProperty("rms_plain", std::to_string(plain_rms));
  RecordProperty("rms_restored", std::to_string(restored_rms));
  EXPECT_LT(restored_rms, plain_rms);
  // Measured 4.44 -> 3.73 codes rms (4.00 while the prior's narrow filter let the luminance through, below; the 3.52
  // this comment gave before was stale). The luminance alone (2x2 means, which hold no carrier) moves the other way,
  // 341 -> 473 (L2 over the frame; 602 before the filter's change, and the 348 -> 450 given before stale too):
  // smoothing the carriers' colour leaks into it where the colour changes within a tile, at the sharp rims of the
  // micro-images. Recorded, not asserted; BENCHMARKS.md has the decoded views' figures.
  cv::Mat truth_luma, plain_luma, restored_luma;
  cv::resize(mosaic.codes, truth_luma, cv::Size(kSize / 2, kSize / 2), 0, 0, cv::INTER_AREA);
  cv::resize(decoded, plain_luma, cv::Size(kSize / 2, kSize / 2), 0, 0, cv::INTER_AREA);
  cv::resize(restored, restored_luma, cv::Size(kSize / 2, kSize / 2), 0, 0, cv::INTER_AREA);
  RecordProperty("luma_l2_plain", std::to_string(cv::norm(truth_luma, plain_luma, cv::NORM_L2)));
  RecordProperty("luma_l2_restored", std::to_string(cv::norm(truth_luma, restored_luma, cv::NORM_L2)));
}

// The prior takes out colour, not light. A carrier that alternates along one axis turns the luminance into a signal at
// the Nyquist frequency; a narrow Gaussian alone passed 1.4 % of it at sigma 1, so every round took 2.9 % of the
// luminance out as colour, and the projection put back only what the DC bins forced (each block's mean to within half
// a code of its recorded value). A grey lenslet mosaic, 60 codes above black at its micro-images' centres, came out
// 2.21 codes darker than its truth on average, against 0.24 for the plain decode; now 0.30.
TEST(JpegMosaic, RestorationKeepsAGreyMosaicsBrightness) {
  TempDir dir;
  const FaintLensletMosaic mosaic(false, 60.0);
  WriteImage(AsBytes(mosaic.codes), dir / "grey.jpg", 8, {{"Compression", "jpeg:75"}});
  const JpegCoefficients coefficients = *ReadJpegCoefficients(dir / "grey.jpg");
  MosaicRestoreOptions plain;
  plain.iterations = 0;
  const double truth = cv::mean(mosaic.codes)[0];
  const double plain_darker = truth - cv::mean(RestoreJpegMosaic(coefficients, plain))[0];
  const double restored_darker = truth - cv::mean(RestoreJpegMosaic(coefficients))[0];
  RecordProperty("plain_mean_darker_codes", std::to_string(plain_darker));
  RecordProperty("restored_mean_darker_codes", std::to_string(restored_darker));
  EXPECT_LT(std::abs(restored_darker - plain_darker), 0.2);
}

// The projection onto a file's bins, given room for the rounding to codes (60 % of each bin), gives a mosaic that an
// encoder stores as the same coefficients: here the grey mosaic moved into the coloured one's bins. e2e/jpeg_capture
// builds that way a capture of other colours with the same JPEG as a simulated one.
TEST(JpegMosaic, ProjectionOntoTheBinsGivesAMosaicThatStoresTheSameJpeg) {
  TempDir dir;
  const FaintLensletMosaic coloured;
  WriteImage(AsBytes(coloured.codes), dir / "coloured.jpg", 8, {{"Compression", "jpeg:75"}});
  const JpegCoefficients stored = ReadJpegCoefficients(dir / "coloured.jpg").value();
  const cv::Mat grey = FaintLensletMosaic(false).codes;
  cv::Mat mosaic = grey.clone();
  for (int round = 0; round < 10; ++round) {
    ProjectOntoJpegBins(stored, mosaic, 0.6);
    AsBytes(mosaic).convertTo(mosaic, CV_32FC1);
  }
  WriteImage(AsBytes(mosaic), dir / "projected.jpg", 8, {{"Compression", "jpeg:75"}});
  const JpegCoefficients again = ReadJpegCoefficients(dir / "projected.jpg").value();
  ASSERT_EQ(again.indices.size(), stored.indices.size());
  EXPECT_EQ(again.quant, stored.quant);
  int same_blocks = 0;
  for (int by = 0; by < stored.blocks_y; ++by)
    for (int bx = 0; bx < stored.blocks_x; ++bx) same_blocks += stored.SameBlock(again, bx, by);
  const int blocks = stored.blocks_x * stored.blocks_y;
  RecordProperty("blocks_stored_alike", std::to_string(same_blocks) + " of " + std::to_string(blocks));
  // Every block but those where libjpeg's integer DCT and the float one round a coefficient apart (2 of 4096).
  EXPECT_GE(same_blocks, blocks * 99 / 100);
  // It moved: the grey mosaic's blocks are not in the coloured file's bins.
  EXPECT_GT(cv::norm(mosaic, grey, cv::NORM_L1) / grey.total(), 0.5);
  cv::Mat wrong_size(8, 8, CV_32FC1, cv::Scalar(0));
  EXPECT_NE(ErrorOf([&] { ProjectOntoJpegBins(stored, wrong_size); }).find("is 8 x 8 float; the file's 64 x 64 blocks"),
            std::string::npos)
      << ErrorOf([&] { ProjectOntoJpegBins(stored, wrong_size); });
  for (const double fraction : {0.0, 1.5, std::nan("")})
    EXPECT_NE(ErrorOf([&] { ProjectOntoJpegBins(stored, mosaic, fraction); }).find("is outside (0, 1]"),
              std::string::npos);
}

// The rounds start from the plain decode unless told otherwise: started from the plain decode as returned, the same
// bytes where no pixel was clamped (a brighter mosaic), within 0.1 codes where some were (the returned decode is
// clamped to 0..255, the rounds' own start keeps the ringing beyond; measured 0.057); started from another mosaic,
// another result; a start of the wrong size is refused.
TEST(JpegMosaic, RestorationStartsWhereItIsTold) {
  TempDir dir;
  MosaicRestoreOptions plain;
  plain.iterations = 0;
  const auto restore_from_plain = [&](const cv::Mat& codes, const std::string& name) {
    WriteImage(AsBytes(codes), dir / name, 8, {{"Compression", "jpeg:75"}});
    const JpegCoefficients coefficients = ReadJpegCoefficients(dir / name).value();
    MosaicRestoreOptions from_plain;
    from_plain.start = RestoreJpegMosaic(coefficients, plain);
    return std::pair(RestoreJpegMosaic(coefficients, from_plain), RestoreJpegMosaic(coefficients));
  };
  const FaintLensletMosaic mosaic;
  const auto [bright_started, bright_default] = restore_from_plain(mosaic.codes + 60.0, "bright.jpg");
  EXPECT_EQ(cv::norm(bright_started, bright_default, cv::NORM_INF), 0.0);
  const auto [started, restored] = restore_from_plain(mosaic.codes, "mosaic.jpg");
  EXPECT_LT(cv::norm(started, restored, cv::NORM_INF), 0.1);
  const JpegCoefficients coefficients = ReadJpegCoefficients(dir / "mosaic.jpg").value();
  MosaicRestoreOptions from_grey;
  from_grey.start = FaintLensletMosaic(false).codes;
  // Measured 0.21 codes on average.
  EXPECT_GT(cv::norm(RestoreJpegMosaic(coefficients, from_grey), restored, cv::NORM_L1) / restored.total(), 0.1);
  MosaicRestoreOptions wrong;
  wrong.start = cv::Mat(8, 8, CV_32FC1, cv::Scalar(0));
  EXPECT_NE(ErrorOf([&] { (void)RestoreJpegMosaic(coefficients, wrong); }).find("the start is 8 x 8 float"),
            std::string::npos);
}

// A grey surface seen through a colour cast, as the sensor sees daylight: red reads 1 / 1.2 and blue 1 / 1.5 of green
// (BGGR), over the faint lenslet mosaic's black level and micro-images. Its colour carriers are 2-3 codes at the
// micro-images' centres, so the JPEG keeps them in some blocks and zeroes them in others.
cv::Mat GreyUnderACast(double level) {
  const FaintLensletMosaic flat(false, level);
  cv::Mat codes = flat.codes.clone();
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float gain = (y & 1) == 0 ? ((x & 1) == 0 ? 1.5f : 1.0f) : ((x & 1) == 0 ? 1.0f : 1.2f);
      codes.at<float>(y, x) = 10.5f + (codes.at<float>(y, x) - 10.5f) / gain;
    }
  return codes;
}

// How far from grey the micro-images' centres of a GreyUnderACast mosaic read once the cast is taken off: |R / G - 1|
// + |B / G - 1| of the phases' means above black.
double DistanceFromGrey(const cv::Mat& codes) {
  const FaintLensletMosaic flat(false, 100.0);  // its centres are the pixels at full profile
  double sums[3] = {0, 0, 0};
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (flat.codes.at<float>(y, x) < 10.5f + 99.0f) continue;
      const int colour = (y & 1) == 0 ? ((x & 1) == 0 ? 2 : 1) : ((x & 1) == 0 ? 1 : 0);
      const double gain = colour == 2 ? 1.5 : (colour == 0 ? 1.2 : 1.0);
      sums[colour] += gain * (codes.at<float>(y, x) - 10.5) * (colour == 1 ? 0.5 : 1.0);
    }
  return std::abs(sums[0] / sums[1] - 1.0) + std::abs(sums[2] / sums[1] - 1.0);
}

// Restored about the scene's grey (MosaicRestoreOptions::grey_gains, the cast's gains), the blocks whose colour the
// JPEG zeroed come back nearer grey; about the sensor's (a flat mosaic) they stay the cast's opposite, magenta.
// Measured from grey: truth 0.006, plain decode 0.69, restored about the sensor's grey 0.68, about the scene's 0.43
// (the rounds start from the plain decode, whose zeroed blocks are flat, and the bins hold them near it).
TEST(JpegMosaic, AboutTheScenesGreyColourlessBlocksRestoreNearerGrey) {
  TempDir dir;
  const cv::Mat truth = GreyUnderACast(16.0);
  WriteImage(AsBytes(truth), dir / "cast.jpg", 8, {{"Compression", "jpeg:75"}});
  const JpegCoefficients coefficients = *ReadJpegCoefficients(dir / "cast.jpg");
  MosaicRestoreOptions plain;
  plain.iterations = 0;
  MosaicRestoreOptions about_the_scene;
  about_the_scene.grey_gains = {1.5f, 1.0f, 1.0f, 1.2f};
  about_the_scene.grey_black = 10.5f;
  const double truth_distance = DistanceFromGrey(truth);
  const double plain_distance = DistanceFromGrey(RestoreJpegMosaic(coefficients, plain));
  const double sensor_distance = DistanceFromGrey(RestoreJpegMosaic(coefficients));
  const double scene_distance = DistanceFromGrey(RestoreJpegMosaic(coefficients, about_the_scene));
  RecordProperty("truth_distance", std::to_string(truth_distance));
  RecordProperty("plain_distance", std::to_string(plain_distance));
  RecordProperty("sensor_grey_distance", std::to_string(sensor_distance));
  RecordProperty("scene_grey_distance", std::to_string(scene_distance));
  EXPECT_LT(truth_distance, 0.02);
  EXPECT_LT(scene_distance, 0.75 * sensor_distance);
  // Gains of 1 are the sensor's grey: the same bytes as the default, whatever the black level.
  MosaicRestoreOptions unit_gains;
  unit_gains.grey_black = 10.5f;
  const cv::Mat by_default = RestoreJpegMosaic(coefficients);
  EXPECT_EQ(cv::norm(RestoreJpegMosaic(coefficients, unit_gains), by_default, cv::NORM_INF), 0.0);
  // One gain of 2 for every phase, without a black level, changes no colour and scales exactly: through the balanced
  // space and back, the default's bytes.
  MosaicRestoreOptions even_gains;
  even_gains.grey_gains = {2.0f, 2.0f, 2.0f, 2.0f};
  EXPECT_EQ(cv::norm(RestoreJpegMosaic(coefficients, even_gains), by_default, cv::NORM_INF), 0.0);
  MosaicRestoreOptions negative;
  negative.grey_gains = {1.0f, -1.0f, 1.0f, 1.0f};
  EXPECT_NE(ErrorOf([&] { (void)RestoreJpegMosaic(coefficients, negative); }).find("grey gains must be positive"),
            std::string::npos);
}

TEST(JpegMosaic, ColourJpegsAreNotMosaicsAndBrokenFilesAreRefused) {
  TempDir dir;
  WriteImage(cv::Mat(16, 16, CV_8UC3, cv::Scalar(10, 200, 30)), dir / "colour.jpg", 8);
  EXPECT_FALSE(ReadJpegCoefficients(dir / "colour.jpg"));
  const FaintLensletMosaic mosaic;
  WriteImage(AsBytes(mosaic.codes), dir / "mosaic.jpg", 8, {{"Compression", "jpeg:75"}});
  const std::string bytes = lfsp::testing::ReadBytes(dir / "mosaic.jpg");
  lfsp::testing::WriteBytes(dir / "cut.jpg", bytes.substr(0, 200));
  EXPECT_NE(ErrorOf([&] { (void)ReadJpegCoefficients(dir / "cut.jpg"); }).find("cut.jpg: not a readable JPEG"),
            std::string::npos)
      << ErrorOf([&] { (void)ReadJpegCoefficients(dir / "cut.jpg"); });
  EXPECT_NE(ErrorOf([&] { (void)ReadJpegCoefficients(dir.path()); }).find("not a regular file"), std::string::npos);
}

}  // namespace
}  // namespace lfsp::decode
