#pragma once

#include <map>
#include <optional>
#include <string>

#include "lfsp/core/light_field.h"
#include "lfsp/decode/demosaic.h"
#include "lfsp/decode/jpeg_block_gain.h"
#include "lfsp/decode/lattice_gain.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/decode/lytro_metadata.h"
#include "lfsp/decode/raw_packing.h"
#include "lfsp/decode/white_balance.h"

namespace lfsp::decode {

// What colour processing the decoder applies after devignetting.
//   kLinear: the white image divides out the sensor's colour response too (colours balanced to the white image's
//            light), no colour matrix, no gamma: scene-linear RGB, Transfer::kLinear.
//   kCamera: as the camera intended (LFToolbox v0.6 style): the white image keeps the sensor response
//            (normalizedResponses), then white-balance gains, colour matrix (ccm), exposure bias
//            2^modulationExposureBias and sRGB encoding, Transfer::kSrgb.
enum class ColourMode { kLinear, kCamera };
std::string_view ToString(ColourMode mode);
ColourMode ColourModeFromString(const std::string& name);

struct DecodeOptions {
  DemosaicMethod demosaic = DemosaicMethod::kGradient;
  ColourMode colour = ColourMode::kCamera;
  // White balance of kCamera decodes (white_balance.h). None given: the camera's gains from the metadata (what
  // DecodeCaptureFile also chooses for Lytro files; plain raw images get kAuto there).
  std::optional<WhiteBalance> white_balance;
  // An automatic white balance already estimated (a JPEG mosaic's restoration took its grey from one, raw_input.h):
  // kAuto applies it instead of estimating again from the views, so that what the restoration took for grey reads
  // grey in the views.
  std::optional<AutoWhiteBalanceReport> estimated_white_balance;
  bool correct_hot_pixels = true;
  // A pixel brighter than all 8 same-colour neighbours by this much (fraction of white - black) is hot.
  double hot_pixel_margin = 0.2;
  // Sensor pixels whose white-image value is below this fraction of the micro-image peak carry no usable light:
  // they are not divided (noise would explode) and their rays get weight ~0.
  double min_white = 0.05;
  // Mixing of each decoded row with its neighbours against the row alternation of hexagonal sampling (see
  // SoftenRowAlternation); 0 = off. 0.1 measured best on the simulator's captures (PSNR and row-shift energy).
  double dehex = 0.1;
  // Divide out the gain the lens lattice leaves in each view (FlattenLatticeGain in lattice_gain.h): a devignetting
  // error that depends on the offset within the micro-image repeats in every view, where depth reads it as texture at
  // disparity 0. On the full-size F01 two-horses capture without noise and without its white image it took depth
  // from 45 % to 5.9 % BadPix 0.07 (3.2 % with the white image), and changed nothing measurable with it.
  bool flatten_lattice = true;
  // A mosaic stored as JPEG (DecodeCaptureFile sets this from the input): its block size in sensor pixels, 8; 0 for
  // lossless captures. With flatten_jpeg_blocks, the gain each view takes from where its samples fall down the blocks
  // is measured and divided out (FlattenJpegBlockGain in jpeg_block_gain.h).
  int jpeg_block = 0;
  bool flatten_jpeg_blocks = true;
  // Which views to decode. -1: every view of the grid (LFToolbox's 4D grid). N > 0: the central N x N. 0: the
  // central square a stage keeps by default (ChooseViews: every view well lit), judged before slicing from the white
  // image with a margin (kDecodeChoiceMargin), so that the exact choice on the decoded weights lies inside it. The
  // pipeline decodes only what it keeps: slicing, gains and storage then cost what the kept views cost.
  int central_views = -1;
};

// How far below kWellLitWeight (view_crop.h) a view's white-image estimate of its mean weight may read and still be
// decoded for central_views = 0. Against the decoded means, the estimate (ApproximateViewMeanWeights) reads within
// 0.006 (simulated Illum) and 0.012 (simulated and real F01) for views above 0.25; only the dim rim's views, which
// no choice keeps, read up to 0.055 off. The Illum's 11x11 ring reads 0.370 at its dimmest (decoded 0.370), so its
// 9x9 is sliced; the F01's 9x9 ring reads below 0.38 at its corners too, so its 7x7 is (the simulated two-horses
// capture's pipeline: the same disparity.pfm as with the whole grid).
inline constexpr double kDecodeChoiceMargin = 0.02;

// The decoded 4D grid of a lattice, as LFToolbox sizes it: n = even(ceil(spacing)), views = n - 1 (Illum 15, F01 9),
// one view step = spacing / n sensor pixels in the lattice frame; decoded pixel (x, y) sits at x * sqrt(3)/2 lens
// pitches along lens row y (hexagonal to rectangular), width = floor((columns - 1) * 2/sqrt(3)) + 1, height = rows.
struct DecodedGeometry {
  int views = 0;
  double view_step = 0.0;
  int width = 0;
  int height = 0;
};
DecodedGeometry DecodedGeometryFor(const LensletGrid& grid);

struct DecodeReport {
  std::string demosaic;
  std::string colour;
  nlohmann::json white_balance;  // mode, gains (R, G, B) and, for auto, what the estimate saw
  long hot_pixels_corrected = 0;
  long clipped_samples = 0;         // sensor samples at the raw ceiling (kClippedLevel of white - black)
  long highlights_neutralised = 0;  // pixels NeutraliseClippedHighlights limited (highlights.h)
  double output_scale = 1.0;        // the factor that brought the brightest decoded sample to <= 1 (no clipping)
  double row_alternation = 0.0;     // RowAlternationRatio of the result (~1 clean, > 2 striped)
  // ChromaBandRatio and LumaBandRatio of the centre view (view_bands.h: clean decodes read 1.8-2.9)
  std::array<double, 2> centre_bands = {0.0, 0.0};
  std::optional<LatticeGainReport> lattice_gain;       // what FlattenLatticeGain found; none when it did not run
  std::optional<JpegBlockGainReport> jpeg_block_gain;  // what FlattenJpegBlockGain found; none when it did not run
  std::map<std::string, double> seconds;               // wall time per step
  std::map<std::string, double> cpu_seconds;           // CPU time per step, all threads
  std::map<std::string, double> resident_mb;           // the process's resident memory at the end of each step
  std::map<std::string, double> peak_resident_mb;      // the process's peak resident memory up to the end of each step
  nlohmann::json ToJson() const;
};

// A white image made ready for devignetting (once per white image, like its grid model): the reciprocal of the
// normalised white (devignetting becomes a product) and its grey version (weights, grid fitting).
struct PreparedWhite {
  cv::Mat inverse;  // CV_32FC1, 1 / max(min_white, white / its 99.9th percentile), per Bayer pixel
  cv::Mat grey;     // CV_32FC1, WhiteImageToGrey
  RawFormat format;
  ColourMode colour = ColourMode::kCamera;  // which white balance `inverse` was made for
  std::string source;
};
PreparedWhite PrepareWhite(const RawImage& white, const LytroMetadata& white_metadata, ColourMode colour,
                           double min_white = DecodeOptions{}.min_white);

// A white image estimated from the capture itself (for raws that come without one): the micro-image vignetting
// profile, averaged over every unclipped lit lens by its offset from the lens centre after dividing each micro-image
// by its own core brightness per Bayer phase (so the scene's brightness and colour cancel), per tile of the sensor
// (up to 5 x 5, blended), times the sensor's response per phase (normalizedResponses, else the inverse white
// balance, else flat), in the capture's raw format. The smooth main-lens falloff across the sensor cannot be told
// from the scene in one capture and is not included. lfsp::Error naming the source when too few lenses are usable.
struct CaptureWhiteReport {
  int lenses = 0;       // lenses of the grid
  int lenses_used = 0;  // unclipped, fully on the sensor, every Bayer phase lit
  int tiles = 0;        // per axis
  // The profile of the lattice's shifted lens rows over the unshifted rows' at 0.4 spacings along the row from the
  // lens centre: 1 on the simulator, 1.011-1.013 on the real F01 frames (each kind of row gets its own profile).
  double shifted_rows_rim_ratio = 1.0;
};
RawImage EstimateWhiteImageFromCapture(const RawImage& capture, const LytroMetadata& metadata, const LensletGrid& grid,
                                       CaptureWhiteReport* report = nullptr);

// Decodes a raw lenslet capture into a light field (views x views of width x height, RGB, per-ray weights from the
// white image): levels from both metadata, hot-pixel correction, devignetting by the white image, demosaicking,
// then ONE interpolation pass from the demosaicked sensor image straight into the 4D grid (each output sample's
// sensor position comes from the grid model; along each lens row the two nearest micro-lenses are blended, which
// is the hexagonal-to-rectangular resampling), then colour. Values are scaled so that nothing clips.
// lfsp::Error (naming the files) on a raw or white buffer of the wrong size, mismatched sensors or missing levels.
LightField DecodeLenslet(const RawImage& capture, const LytroMetadata& capture_metadata, const RawImage& white,
                         const LytroMetadata& white_metadata, const LensletGrid& grid,
                         const DecodeOptions& options = {}, DecodeReport* report = nullptr);
// The same with a prepared white image (its colour mode must match options.colour; options.min_white is the one it
// was prepared with).
LightField DecodeLenslet(const RawImage& capture, const LytroMetadata& capture_metadata, const PreparedWhite& white,
                         const LensletGrid& grid, const DecodeOptions& options = {}, DecodeReport* report = nullptr);
// The same, consuming the capture and the prepared white image: each buffer is freed as soon as the decode is done
// with it (the capture after levelling; the white image's inverse then too, or after the highlights when samples
// clipped; its grey version after the slicing), so that none is resident beside the demosaicked image and the light
// field (an Illum's: 83 MB, 166 MB, 166 MB). The light field is the same bit for bit.
LightField DecodeLenslet(RawImage&& capture, const LytroMetadata& capture_metadata, PreparedWhite&& white,
                         const LensletGrid& grid, const DecodeOptions& options = {}, DecodeReport* report = nullptr);

}  // namespace lfsp::decode
