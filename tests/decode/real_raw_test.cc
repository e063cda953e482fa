// The lenslet grid of real Lytro data that comes without white images or metadata (issue 13): three real F01 raw
// frames (../shared/data/lytro_raw/tao_f01, JPEG) against the camera's own table of lens centres, and a real
// white-image crop against LFToolbox's centres. Skipped without ../shared/data.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "lfsp/core/image_io.h"
#include "lfsp/decode/capture_decoder.h"
#include "lfsp/decode/jpeg_block_gain.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/raw_input.h"
#include "test_support.h"

namespace lfsp::decode {
namespace {

namespace fs = std::filesystem;
using lfsp::testing::ErrorOf;
using lfsp::testing::TempDir;

struct Point {
  double x = 0.0;
  double y = 0.0;
};

// `grid_i grid_j row col` rows (0-based pixels) or `x y` rows; '#' lines are comments.
std::vector<Point> ReadCentres(const fs::path& path, bool row_col_table) {
  std::ifstream file(path);
  std::vector<Point> centres;
  std::string line;
  while (std::getline(file, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Point p;
    if (row_col_table) {
      double i = 0.0, j = 0.0;
      fields >> i >> j >> p.y >> p.x;
    } else {
      fields >> p.x >> p.y;
    }
    if (fields) centres.push_back(p);
  }
  return centres;
}

// Distance from each reference centre to the fitted lattice's nearest lens centre (the lattice extends past the
// usable grid, so partial border lenses count too).
std::vector<double> Distances(const LensletGrid& grid, const std::vector<Point>& reference) {
  std::vector<double> distances;
  distances.reserve(reference.size());
  for (const Point& p : reference) {
    int i = 0, j = 0;
    grid.Nearest(p.x, p.y, i, j);
    double x = 0.0, y = 0.0;
    grid.Centre(i, j, x, y);
    distances.push_back(std::hypot(x - p.x, y - p.y));
  }
  std::sort(distances.begin(), distances.end());
  return distances;
}

double Quantile(const std::vector<double>& sorted, double q) {
  return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
}

GridEstimate GridOf(const fs::path& image, const std::string& camera, LensletImageKind kind) {
  PlainRawOptions options;
  options.camera = camera;
  const RawInput input = OpenRawInput(image, options);
  const std::optional<GridGuess> guess =
      input.metadata.mla ? std::optional(GuessFromMetadata(input.metadata, input.raw.width, input.raw.height))
                         : std::nullopt;
  return FindLensletGrid(WhiteImageToGrey(input.raw, *input.metadata.raw_format, image.string()), guess, kind);
}

TEST(RealRawGrid, ThreeF01FramesMatchTheCamerasCentreTable) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path folder = data / "lytro_raw" / "tao_f01";
  const std::vector<Point> table = ReadCentres(folder / "image_cords_rowcol_0based.txt", true);
  ASSERT_GT(table.size(), 100000u);
  for (const char* frame : {"IMG_1.jpg", "IMG_2.jpg", "IMG_3.jpg"}) {
    SCOPED_TRACE(frame);
    const GridEstimate estimate = GridOf(folder / frame, "f01", LensletImageKind::kAuto);
    const LensletGrid& grid = estimate.grid;
    EXPECT_EQ(grid.fit_method, "capture periodicity");  // a scene, not a white image
    // The whole sensor: about 330 lenses per row (pitch 9.93 px) and 380 rows (8.6 px apart) on 3280 x 3280.
    EXPECT_GE(grid.columns, 325);
    EXPECT_GE(grid.rows, 375);
    const std::vector<double> d = Distances(grid, table);
    // The table's centres are integers: a perfect lattice scores a median of about 0.40 px, and the best lattice of
    // our model fitted to the table itself 0.410 / p95 0.702. Measured 0.412-0.419 / 0.709-0.739 (issue 49, item 5);
    // 0.415-0.425 / 0.723-0.757 while the colour carriers' sidebands reached the lattice's contrast (BENCHMARKS.md,
    // thirty-ninth session, which lists the earlier figures too).
    EXPECT_LE(Quantile(d, 0.5), 0.45);
    EXPECT_LE(Quantile(d, 0.95), 0.75);
    const auto within = std::upper_bound(d.begin(), d.end(), 1.5) - d.begin();
    EXPECT_GE(static_cast<double>(within) / static_cast<double>(d.size()), 0.99);
    RecordProperty(std::string(frame) + "_median_px", std::to_string(Quantile(d, 0.5)));
    RecordProperty(std::string(frame) + "_p95_px", std::to_string(Quantile(d, 0.95)));
  }
}

TEST(RealRawGrid, WhiteImageCropMatchesLfToolboxCentres) {
  LFSP_REQUIRE_SHARED_DATA(data);
  const fs::path folder = data / "lytro" / "white_image_crop";
  const std::vector<Point> reference = ReadCentres(folder / "lftoolbox_centres_px.txt", false);
  ASSERT_EQ(reference.size(), 288u);
  // No camera, no metadata: spacing, rotation and position from the image alone, then per-lens centroids.
  const GridEstimate estimate = GridOf(folder / "white_crop.png", "", LensletImageKind::kAuto);
  EXPECT_EQ(estimate.grid.fit_method, "white-image centroids");
  const std::vector<double> d = Distances(estimate.grid, reference);
  EXPECT_LE(Quantile(d, 0.5), 0.15);
  EXPECT_LE(Quantile(d, 0.95), 0.5);
  RecordProperty("median_px", std::to_string(Quantile(d, 0.5)));
}

// The mean of a view's luminance (the channels' mean) minus the mean of the rows above and below, times (-1)^row: how
// much the view's rows alternate in brightness on average.
double SignedRowAlternation(const LightField& light_field, ViewIndex view) {
  const LightFieldShape& shape = light_field.shape();
  const auto luminance = [&](int y, int x) {
    double sum = 0.0;
    for (int c = 0; c < shape.channels; ++c) sum += light_field.at(view, y, x, c);
    return sum / shape.channels;
  };
  double sum = 0.0;
  for (int y = 1; y + 1 < shape.height; ++y)
    for (int x = 0; x < shape.width; ++x)
      sum += (y % 2 ? -1.0 : 1.0) * (luminance(y, x) - 0.5 * (luminance(y - 1, x) + luminance(y + 1, x)));
  return sum / ((shape.height - 2.0) * shape.width);
}

// Channel means (R, G, B) of the centre view, as stored (sRGB): of every pixel, or of the brightest `share` of them
// (by R + G + B).
std::array<double, 3> CentreMeans(const LightField& light_field, double share = 1.0) {
  const LightFieldShape& shape = light_field.shape();
  std::vector<std::array<double, 3>> pixels;
  for (int y = 0; y < shape.height; ++y)
    for (int x = 0; x < shape.width; ++x)
      pixels.push_back({light_field.at(shape.Centre(), y, x, 0), light_field.at(shape.Centre(), y, x, 1),
                        light_field.at(shape.Centre(), y, x, 2)});
  const auto count = std::max<std::size_t>(1, static_cast<std::size_t>(share * static_cast<double>(pixels.size())));
  std::partial_sort(pixels.begin(), pixels.begin() + static_cast<std::ptrdiff_t>(count), pixels.end(),
                    [](const auto& a, const auto& b) { return a[0] + a[1] + a[2] > b[0] + b[1] + b[2]; });
  std::array<double, 3> means{};
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) means[static_cast<std::size_t>(c)] += pixels[i][static_cast<std::size_t>(c)];
  for (double& m : means) m /= static_cast<double>(count);
  return means;
}

// A real F01 frame of lytro_raw/tao_f01 decoded as `lfsp decode FRAME --camera f01 [--jpeg-grey scene]` would.
CaptureDecodeResult DecodeRealFrame(const fs::path& data, const std::string& frame, JpegGrey grey) {
  CaptureDecodeOptions options;
  options.plain.camera = "f01";
  options.plain.jpeg_grey = grey;
  return DecodeCaptureFile(data / "lytro_raw" / "tao_f01" / frame, options);
}

// Issue 49's colour rules on a real frame's centre-view means (R, G, B): blue not above the larger of red and green
// by more than `blue_margin` (a share), the means within 1.6x of each other, IMG_3's leaves green. The means are
// recorded as `property`.
void ExpectNaturalColour(const std::string& frame, const std::array<double, 3>& means, double blue_margin,
                         const std::string& property) {
  ::testing::Test::RecordProperty(
      property, std::to_string(means[0]) + " " + std::to_string(means[1]) + " " + std::to_string(means[2]));
  EXPECT_LT(means[2], (1.0 + blue_margin) * std::max(means[0], means[1]));
  EXPECT_LT(*std::max_element(means.begin(), means.end()) / *std::min_element(means.begin(), means.end()), 1.6);
  if (frame == "IMG_3.jpg") {
    EXPECT_GT(means[1], std::max(means[0], means[2]));  // green leaves
  }
}

// The real frames decode end to end with the lattice and vignetting from the frame itself (issue 13), and look
// right (issue 49): the JPEG's colour damage restored (no colour bands), the black level taken off, and a white
// balance from the frame's own grey surfaces instead of a blue cast.
TEST(RealRawDecode, F01FramesDecodeWithoutBandsOrColourCast) {
  LFSP_REQUIRE_SHARED_DATA(data);
  for (const char* frame : {"IMG_1.jpg", "IMG_2.jpg", "IMG_3.jpg"}) {
    SCOPED_TRACE(frame);
    const CaptureDecodeResult result = DecodeRealFrame(data, frame, JpegGrey::kSensor);
    const LightFieldShape& shape = result.light_field.shape();
    EXPECT_EQ(shape.nu, 9);
    EXPECT_GE(shape.width, 370);
    EXPECT_GE(shape.height, 370);
    EXPECT_EQ(result.summary["white_image"]["name"], "estimated from the capture");
    EXPECT_GT(result.summary["white_image"]["lenses_used"].get<int>(), 100000);
    // The lattice's shifted lens rows have brighter rims along the row than the unshifted ones (relative to their
    // centres), by 1.12 / 1.24 / 1.32 % at 0.4 spacings; the simulator's rows are alike (0.99994). The white image
    // follows each kind of row, so the outer views' rows no longer alternate in brightness (issue 49).
    const double rim_ratio = result.summary["white_image"]["shifted_rows_rim_ratio"].get<double>();
    RecordProperty(std::string(frame) + "_shifted_rows_rim_ratio", std::to_string(rim_ratio));
    EXPECT_GT(rim_ratio, 1.005);
    EXPECT_LT(rim_ratio, 1.03);
    // The outermost views of the middle row alternate no more than the centre view plus 0.8e-3: with one profile for
    // both kinds of row they read 1.3 / 2.2 / 1.6e-3 more than it (IMG_1-3), now 0.3-0.5e-3.
    const ViewIndex centre = shape.Centre();
    const double outer_excess = 0.5 * (std::abs(SignedRowAlternation(result.light_field, {0, centre.v})) +
                                       std::abs(SignedRowAlternation(result.light_field, {shape.nu - 1, centre.v}))) -
                                std::abs(SignedRowAlternation(result.light_field, centre));
    RecordProperty(std::string(frame) + "_outer_views_row_alternation_excess", std::to_string(outer_excess));
    EXPECT_LT(outer_excess, 0.8e-3);
    const double alternation = result.summary["decode"]["row_alternation"].get<double>();
    RecordProperty(std::string(frame) + "_row_alternation", std::to_string(alternation));
    // The simulator's correct decodes read 1..3 and a wrong row shift above 20. The plain JPEG decode read 1.0-3.6
    // here; the restoration ending on its projection read 6.5-6.9 (IMG_2, IMG_3), the lattice gain's rms 0.0021 ->
    // 0.0035: smoothing
    // the carriers' colour at the wide scale also smooths the lens lattice's harmonics that fall near the carriers
    // (the 5th across, 0.058 cycles/px from (pi, 0); the 4th down, 0.035 from (0, pi)). Not visible in the views;
    // kept under watch here. Ending the restoration on its prior took IMG_2 from 6.97 to 10.6 and IMG_3 from 6.42 to
    // 7.59 while the alternating energy itself fell (by 7 and 19 %): the ratio's reference band just below it (0.40-
    // 0.47 cycles per row) lost 39 and 31 %, the chroma speckle the last projection had put back (BENCHMARKS.md,
    // thirty-seventh session). Since the prior's narrow filter keeps the luminance out of the colour: 3.0 / 9.7 / 6.9.
    EXPECT_LT(alternation, 12.0);

    // The JPEG restoration ran, and the black level is the camera's, scaled to 8 bits.
    EXPECT_EQ(result.summary["jpeg_restoration"]["iterations"], PlainRawOptions{}.jpeg_restore_iterations);
    EXPECT_NE(result.summary["levels"].get<std::string>().find("black 10.46"), std::string::npos);
    // Bands, in the order the decoder gained them (IMG_1-3): the plain JPEG decode read 3.3 / 7.5 / 11.5, the first
    // restoration 3.1 / 4.9 / 5.7; clean decodes by other tools read 1.8-2.9. The gain each view takes from where its
    // samples fall down the JPEG's blocks was then divided out (jpeg_block_gain.h): the luminance that follows the
    // blocks' rows fell from 0.25 / 0.69 / 0.52 % to 0.09 / 0.06 / 0.11 %, and IMG_2's chroma bands from 4.88 to 4.21,
    // while IMG_1 and IMG_3 kept 3.1 and 5.8. What IMG_3 reads there does not follow the blocks: on IMG_3 it sits on
    // the veins of the leaf at the right, moves between views with the scene's parallax, and keeps one phase across the
    // width, where the blocks' rows turn through two cycles (BENCHMARKS.md). The simulator's ground truth of
    // two-horses, without any JPEG, reads 3.7 on the same measure. Ending the restoration on its prior (the last
    // projection's per-block clamps left out): 3.08 / 4.19 / 5.57 -> 3.10 / 3.10 / 5.04. The prior's narrow filter
    // zero at the Nyquist frequency, so that it no longer takes 2.9 % of the luminance and of every carrier's colour
    // out a round: 2.85 / 3.37 / 5.58, today's figures. IMG_3's veins keep more colour; IMG_2's centre view is among
    // the higher of its central 7 x 7 views (median 2.48, 2.46 before).
    const double block_locked =
        BlockRowLuminance(result.light_field, shape.Centre(), LensletGrid::FromJson(result.summary["grid"], frame),
                          result.light_field.metadata["decode"]["view_step_pixels"]);
    const double bands = result.summary["decode"]["centre_bands"]["chroma"].get<double>();
    const double luma_bands = result.summary["decode"]["centre_bands"]["luma"].get<double>();
    RecordProperty(std::string(frame) + "_block_locked_luma_percent", std::to_string(block_locked));
    RecordProperty(std::string(frame) + "_chroma_bands", std::to_string(bands));
    RecordProperty(std::string(frame) + "_luma_bands", std::to_string(luma_bands));
    // IMG_1-3 read 0.067 / 0.051 / 0.078 % before the restoration ended on its prior, 0.081 / 0.049 / 0.183 % after,
    // 0.054 / 0.035 / 0.068 % since its prior leaves the luminance alone (its darkening, pinned to each block's DC
    // bin, followed the blocks); the plain JPEG decode of the simulated capture reads 3.3 % before the gain is
    // divided out.
    EXPECT_LT(block_locked, 0.12);
    EXPECT_GT(result.summary["decode"]["jpeg_block_gain"]["views"].get<int>(), 60);
    EXPECT_LT(bands, 6.5);
    if (std::string(frame) == "IMG_2.jpg") {
      EXPECT_LT(bands, 3.6);
    }
    // Colour: automatic white balance (no blue cast: blue was the largest mean on all three), means within 1.6x.
    // IMG_2 (a white shoe on a purple carpet) reads blue and red level, 0.5586 and 0.5586 (G 0.5196), since the
    // restoration keeps the carpet's colour: blue may reach red or green by 0.1 %, no further.
    EXPECT_EQ(result.summary["decode"]["white_balance"]["mode"], "auto");
    ExpectNaturalColour(frame, CentreMeans(result.light_field), 0.001, std::string(frame) + "_means");
    if (std::string(frame) == "IMG_1.jpg") {
      // The brightest 1 %, white petals the sensor clipped, read neutral: blue 1.03 x red (1.21 before clipped
      // highlights were neutralised), 1.03 x green.
      EXPECT_GT(result.summary["decode"]["highlights_neutralised"].get<long>(), 10000);
      const std::array<double, 3> brightest = CentreMeans(result.light_field, 0.01);
      EXPECT_LT(brightest[2] / brightest[0], 1.08);
      EXPECT_LT(brightest[2] / brightest[1], 1.08);
    }
  }
}

// `--jpeg-grey scene` (PlainRawOptions::jpeg_grey): the restoration takes the scene's grey for colourless, the white
// balance of a short first restoration, and the decode applies those gains. Measured (IMG_1-3): chroma bands 2.08 /
// 2.60 / 2.07 against the default's 2.83 / 3.39 / 5.78, luma 2.46 / 3.49 / 4.93 against 2.56 / 3.47 / 5.46; IMG_2's
// blue 0.501 under red 0.517 (the default: level, 0.5587 each). Issue 49's colour rules hold; the bands stay under 3.0
// on all three, the clean decodes' range.
TEST(RealRawDecode, F01FramesRestoredAboutTheScenesGreyHaveNoColourBands) {
  LFSP_REQUIRE_SHARED_DATA(data);
  for (const char* frame : {"IMG_1.jpg", "IMG_2.jpg", "IMG_3.jpg"}) {
    SCOPED_TRACE(frame);
    const CaptureDecodeResult result = DecodeRealFrame(data, frame, JpegGrey::kScene);
    const nlohmann::json& grey = result.summary["jpeg_restoration"]["grey"];
    const nlohmann::json& balance = result.summary["decode"]["white_balance"];
    EXPECT_EQ(balance["mode"], "auto");
    EXPECT_EQ(balance["gains"], grey["gains"]);  // what the restoration took for grey is grey in the views
    EXPECT_NE(balance["auto"]["from"].get<std::string>().find("JPEG restoration"), std::string::npos);
    const double bands = result.summary["decode"]["centre_bands"]["chroma"].get<double>();
    RecordProperty(std::string(frame) + "_scene_grey_chroma_bands", std::to_string(bands));
    EXPECT_LT(bands, 3.0);
    const std::array<double, 3> means = CentreMeans(result.light_field);
    ExpectNaturalColour(frame, means, 0.0, std::string(frame) + "_scene_grey_means");
    if (std::string(frame) == "IMG_2.jpg") {
      EXPECT_LT(means[2], means[0]);  // the shoe's blue under its red (level by default)
    }
  }
}

// Without the shared data: a small F01-like JPEG mosaic read with `--jpeg-grey scene` records the estimate it restored
// about, the gains it applied per phase are those of the summary, and the default records the sensor's grey.
TEST(RealRawDecode, AJpegMosaicRestoredAboutTheScenesGreyRecordsIt) {
  TempDir dir;
  cv::Mat mosaic(128, 128, CV_8UC1);
  for (int y = 0; y < mosaic.rows; ++y)
    for (int x = 0; x < mosaic.cols; ++x) {
      // BGGR: a grey surface seen with red as green and blue at 1 / 1.4 of it (a light near the F01's, whose gains
      // the search starts from: the colour matrix makes a far one look too coloured to be grey), lit from 30 to
      // 100 % across (the estimate leaves out the brightest tiles as clipped).
      const double colour = (y & 1) == 0 ? ((x & 1) == 0 ? 1.0 / 1.4 : 1.0) : 1.0;
      mosaic.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(10.5 + 150.0 * (0.3 + 0.7 * x / 127.0) * colour);
    }
  WriteImage(mosaic, dir / "mosaic.jpg", 8, {{"Compression", "jpeg:95"}});
  PlainRawOptions options;
  options.camera = "f01";
  options.jpeg_grey = JpegGrey::kScene;
  const RawInput scene = OpenRawInput(dir / "mosaic.jpg", options);
  ASSERT_TRUE(scene.jpeg_scene_grey);
  EXPECT_EQ(scene.jpeg_restoration["grey"]["gains"], nlohmann::json(scene.jpeg_scene_grey->gains));
  EXPECT_NEAR(scene.jpeg_scene_grey->gains[0], 1.0, 0.05);
  EXPECT_NEAR(scene.jpeg_scene_grey->gains[2], 1.4, 0.05);
  options.jpeg_grey = JpegGrey::kSensor;
  const RawInput sensor = OpenRawInput(dir / "mosaic.jpg", options);
  EXPECT_FALSE(sensor.jpeg_scene_grey);
  EXPECT_EQ(sensor.jpeg_restoration["grey"], "the sensor's: a flat mosaic");
}

TEST(RealRawDecode, TheScenesGreyNeedsACamera) {
  TempDir dir;
  cv::Mat mosaic(64, 64, CV_8UC1, cv::Scalar(40));
  WriteImage(mosaic, dir / "mosaic.jpg", 8, {{"Compression", "jpeg:75"}});
  PlainRawOptions options;
  options.jpeg_grey = JpegGrey::kScene;
  EXPECT_NE(ErrorOf([&] { (void)OpenRawInput(dir / "mosaic.jpg", options); }).find("jpeg_grey scene needs camera"),
            std::string::npos)
      << ErrorOf([&] { (void)OpenRawInput(dir / "mosaic.jpg", options); });
  EXPECT_EQ(JpegGreyFromString("scene"), JpegGrey::kScene);
  EXPECT_EQ(ToString(JpegGrey::kSensor), "sensor");
  EXPECT_NE(ErrorOf([] { (void)JpegGreyFromString("grey"); }).find("expected sensor or scene"), std::string::npos);
}

}  // namespace
}  // namespace lfsp::decode
