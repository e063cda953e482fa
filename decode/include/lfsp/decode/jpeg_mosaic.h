#pragma once

// Bayer mosaics stored as greyscale JPEG, as some exports of lenslet raws are (the real F01 frames of Tao et al.,
// ICCV 2013, are 8-bit quality-75 JPEGs of the mosaic).
//
// Why they need more than an ordinary JPEG decode: a Bayer mosaic carries its colour at the highest spatial
// frequencies (G against R and B is a checkerboard, R against B alternates along rows and columns), which is exactly
// what JPEG quantizes hardest. Where the colour is faint, as in a dark frame, most blocks keep only the (7,7)
// coefficient of the checkerboard, or nothing: the decoded colour then swells and fades with the position inside
// each 8x8 block (the basis function's |cos| envelope, 0.2 at the block edge to 1.0 at its centre), and vanishes in
// whole blocks. Micro-lens rows 8.6 px apart sample those 8-px cycles at a slowly drifting phase, so every view
// shows colour bands about 14 rows apart. RestoreJpegMosaic undoes what it can from the coefficients themselves.

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace lfsp::decode {

// The quantized DCT coefficients of a single-component JPEG, as stored in the file.
struct JpegCoefficients {
  int width = 0;  // image size in pixels
  int height = 0;
  int blocks_x = 0;  // 8x8 blocks per row and rows of blocks (the last ones may reach past the image)
  int blocks_y = 0;
  std::array<float, 64> quant{};      // quantization step of each coefficient, natural (row-major) order
  std::vector<std::int16_t> indices;  // blocks_y x blocks_x blocks of 64 quantized values, natural order
  const std::int16_t* Block(int bx, int by) const {
    return indices.data() +
           (static_cast<std::size_t>(by) * static_cast<std::size_t>(blocks_x) + static_cast<std::size_t>(bx)) * 64;
  }
  // Whether block (bx, by) holds the same 64 quantized values in `other` (same block layout); with the same `quant`,
  // a decoder cannot tell the two blocks apart.
  bool SameBlock(const JpegCoefficients& other, int bx, int by) const {
    return std::equal(Block(bx, by), Block(bx, by) + 64, other.Block(bx, by));
  }
};

// The coefficients of a greyscale (one-component, 8-bit) JPEG, or nothing when the file is a colour or 12-bit JPEG.
// lfsp::Error naming the file when it is not a readable JPEG or declares more blocks than its size can hold
// (CheckDeclaredAllocation).
std::optional<JpegCoefficients> ReadJpegCoefficients(const std::filesystem::path& path);

// The restoration's projection on its own, in place on `image` (CV_32FC1 codes, blocks_x * 8 wide and blocks_y * 8
// high): each block's DCT coefficients move to the nearest point of the central `bin_fraction` of the quantization
// bins the file records (1: the whole bins), then every pixel is clamped to 0..255, which may move a coefficient out
// again (repeat to converge). Less than the whole bin leaves room for rounding the result to 8-bit codes that an
// encoder quantizes back to the same coefficients: e2e/jpeg_capture builds that way a mosaic of other colours that
// stores the same JPEG as a simulated capture.
void ProjectOntoJpegBins(const JpegCoefficients& coefficients, cv::Mat& image, double bin_fraction = 1.0);

struct MosaicRestoreOptions {
  // Alternations between the two constraints below. 0 = the start as given, clamped to 0..255 (by default the plain
  // JPEG decode).
  int iterations = 30;
  // The colour of the mosaic (each Bayer carrier demodulated to base band) is taken to vary smoothly: what lies
  // between these two scales (pixels) around each carrier is taken out at every iteration. The narrow one holds the
  // JPEG block pattern (8-px cycles and their harmonics); the wide one keeps the scene's colour. The narrow filter is
  // a Gaussian of narrow_sigma followed by the binomial (1, 2, 1) / 4 along each axis (together about 1.1 px at
  // 0.85), whose zero at the Nyquist frequency keeps the luminance's local mean out of the demodulated colour
  // (jpeg_mosaic.cc, NarrowCarrierKernel).
  double narrow_sigma = 0.85;
  double wide_sigma = 32.0;
  // Where the rounds start: CV_32FC1 codes covering the file's blocks (blocks_x * 8 by blocks_y * 8, which is more
  // than the result's width x height when the image is not a multiple of 8), or empty for the plain decode. The
  // result depends on it: e2e/jpeg_capture starts from a mosaic of other colours to find a smooth mosaic of those
  // colours near the file's bins.
  cv::Mat start;
  // The colour the prior takes for none. By default the sensor's: every Bayer phase alike, a flat mosaic. A flat
  // mosaic is not grey once the white balance has scaled its channels (magenta under daylight gains), and it is
  // what a block whose colour the quantization zeroed starts from and what the prior draws smooth colour towards.
  // With these gains (per position in the 2x2 tile, row by row: (0,0), (0,1), (1,0), (1,1)) the prior measures
  // colour on (code - grey_black) x gain instead, so that the colour it keeps and the colour it fills in are
  // reckoned from a grey under those gains (`--jpeg-grey scene` passes the scene's: its automatic white balance, per
  // phase; raw_input.cc). The black level is taken off first so that the pedestal is not measured as colour: the
  // prior keeps a constant per phase, but its filters reflect at the border, and the wide scale carries that inwards
  // over the rounds.
  std::array<float, 4> grey_gains = {1.0f, 1.0f, 1.0f, 1.0f};
  float grey_black = 0.0f;  // codes
};

struct MosaicRestoreReport {
  int iterations = 0;
  double mean_change = 0.0;      // mean |restored - plain decode|, codes
  double last_correction = 0.0;  // mean distance the last iteration's coefficients moved back into their bins
};

// An estimate of the mosaic the coefficients came from, in 8-bit codes (CV_32FC1, 0..255, width x height):
// alternating projections (POCS) between "every DCT coefficient lies inside the quantization bin the file
// records" (which holds for the true mosaic) and "the colour carried by the Bayer carriers is smooth". Blocks whose
// colour was quantized away take it from their neighbours, and the block envelope is flattened, within what the
// recorded coefficients allow. Luminance detail away from the carriers is left to the data. The rounds end on the
// prior, not on the projection (jpeg_mosaic.cc, EndOnThePrior, says why): the colour is the smooth estimate, colour
// finer than the wide scale is not kept, and the result lies near the bins rather than exactly in them.
// Deterministic; uses the OpenMP threads.
cv::Mat RestoreJpegMosaic(const JpegCoefficients& coefficients, const MosaicRestoreOptions& options = {},
                          MosaicRestoreReport* report = nullptr);

}  // namespace lfsp::decode
