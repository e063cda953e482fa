// Greyscale JPEG mosaics: reading the quantized coefficients (libjpeg) and restoring the Bayer colour that the
// quantization damaged (see jpeg_mosaic.h for why).

#include "lfsp/decode/jpeg_mosaic.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include "bayer_levels.h"
#include "lfsp/core/banded_filter.h"
#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"

namespace lfsp::decode {
namespace {

// libjpeg reports errors through error_exit, which must not return: it jumps back to the reader with the message.
struct JumpingErrorManager {
  jpeg_error_mgr base{};
  std::jmp_buf jump{};
  char message[JMSG_LENGTH_MAX] = {};
};

void JumpOnError(j_common_ptr info) {
  auto* manager = reinterpret_cast<JumpingErrorManager*>(info->err);
  (*info->err->format_message)(info, manager->message);
  std::longjmp(manager->jump, 1);
}

// A warning (level -1) is corrupt data that libjpeg would patch over, such as a truncated scan filled with grey: a
// mosaic with made-up blocks is refused like any other broken input. Trace messages (level >= 0) are ignored.
void JumpOnWarning(j_common_ptr info, int level) {
  if (level < 0) JumpOnError(info);
}

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

enum class ReadOutcome { kRead, kNotGreyscale, kFailed };

// Everything that can longjmp lives in this function, whose locals are all trivially destructible, so a jump
// skips no destructor. `out` and `problem` belong to the caller.
ReadOutcome ReadCoefficientsInto(std::FILE* file, const std::string& name, JpegCoefficients& out,
                                 std::string& problem) {
  jpeg_decompress_struct info{};
  JumpingErrorManager errors;
  info.err = jpeg_std_error(&errors.base);
  errors.base.error_exit = JumpOnError;
  errors.base.emit_message = JumpOnWarning;
  if (setjmp(errors.jump)) {
    jpeg_destroy_decompress(&info);
    problem = errors.message;
    return ReadOutcome::kFailed;
  }
  jpeg_create_decompress(&info);
  jpeg_stdio_src(&info, file);
  jpeg_read_header(&info, TRUE);
  if (info.num_components != 1 || info.data_precision != 8) {
    jpeg_destroy_decompress(&info);
    return ReadOutcome::kNotGreyscale;
  }
  // The coefficients (2 bytes each) are held twice, by libjpeg and in the copy made here.
  const std::uint64_t blocks = SaturatingBytes({(info.image_width + 7u) / 8u, (info.image_height + 7u) / 8u}, 1);
  try {
    CheckDeclaredAllocation(name, 2 * SaturatingBytes({blocks, 64}, sizeof(std::int16_t)), FileBytes(name));
  } catch (...) {
    jpeg_destroy_decompress(&info);
    throw;
  }
  jvirt_barray_ptr* arrays = jpeg_read_coefficients(&info);
  const jpeg_component_info& component = info.comp_info[0];
  if (component.quant_table == nullptr) {
    jpeg_destroy_decompress(&info);
    problem = "no quantization table";
    return ReadOutcome::kFailed;
  }
  out.width = static_cast<int>(info.image_width);
  out.height = static_cast<int>(info.image_height);
  out.blocks_x = static_cast<int>(component.width_in_blocks);
  out.blocks_y = static_cast<int>(component.height_in_blocks);
  for (int k = 0; k < 64; ++k) out.quant[static_cast<std::size_t>(k)] = component.quant_table->quantval[k];
  out.indices.resize(static_cast<std::size_t>(out.blocks_x) * static_cast<std::size_t>(out.blocks_y) * 64);
  for (int by = 0; by < out.blocks_y; ++by) {
    JBLOCKARRAY row = (*info.mem->access_virt_barray)(reinterpret_cast<j_common_ptr>(&info), arrays[0],
                                                      static_cast<JDIMENSION>(by), 1, FALSE);
    for (int bx = 0; bx < out.blocks_x; ++bx)
      std::copy(row[0][bx], row[0][bx] + 64,
                out.indices.begin() + (static_cast<std::ptrdiff_t>(by) * out.blocks_x + bx) * 64);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return ReadOutcome::kRead;
}

// The orthonormal 8-point DCT-II matrix: coefficient k of samples f is sum_n kDct[k][n] f[n]. JPEG's 2D transform is
// this one along rows and columns.
struct DctMatrix {
  float m[8][8];
  DctMatrix() {
    for (int k = 0; k < 8; ++k)
      for (int n = 0; n < 8; ++n)
        m[k][n] = static_cast<float>((k == 0 ? std::sqrt(0.125) : 0.5) * std::cos((2 * n + 1) * k * M_PI / 16.0));
  }
};
const DctMatrix kDct;

// A row of a block: eight floats, one vector register (AVX) or two (SSE2).
typedef float BlockRow __attribute__((vector_size(32)));

// kDct's rows and columns as block rows, for the broadcast-and-add form of Transform below.
struct DctRows {
  BlockRow row[8];     // row[k][n] = kDct.m[k][n]
  BlockRow column[8];  // column[n][k] = kDct.m[k][n]
  DctRows() {
    for (int k = 0; k < 8; ++k)
      for (int n = 0; n < 8; ++n) {
        row[k][n] = kDct.m[k][n];
        column[n][k] = kDct.m[k][n];
      }
  }
};
const DctRows kDctRows;

// out = M in M^T (forward) or M^T in M (inverse), for one 8x8 block. Each output row is built as a whole row, the
// terms added in the order of the plain sums (n = 0..7 from zero, a product and then a sum each), so every
// coefficient and pixel is the float it would be written element by element.
inline void Transform(const float in[64], float out[64], bool inverse) {
  BlockRow rows[8], temp[8];
  for (int n = 0; n < 8; ++n) __builtin_memcpy(&rows[n], in + 8 * n, sizeof(BlockRow));
  // temp[r][c] = sum_n A[r][n] in[n][c], A = M (forward) or M^T (inverse).
  for (int r = 0; r < 8; ++r) {
    BlockRow sum = {};
    for (int n = 0; n < 8; ++n) sum = sum + (inverse ? kDct.m[n][r] : kDct.m[r][n]) * rows[n];
    temp[r] = sum;
  }
  // out[r][c] = sum_n temp[r][n] B[n][c], B = M^T (forward: B[n][c] = M[c][n]) or M (inverse: B[n][c] = M[n][c]).
  for (int r = 0; r < 8; ++r) {
    BlockRow sum = {};
    for (int n = 0; n < 8; ++n) sum = sum + temp[r][n] * (inverse ? kDctRows.row[n] : kDctRows.column[n]);
    __builtin_memcpy(out + 8 * r, &sum, sizeof(BlockRow));
  }
}

// The pixels (level-shifted by 128, as JPEG codes them) of row `by` of blocks from their dequantized coefficients.
// Built for AVX2 too, where Transform's eight-float rows are one register (Transform is inlined into each build).
__attribute__((target_clones("avx2", "default"))) void DecodeRowOfBlocks(const JpegCoefficients& coefficients, int by,
                                                                         cv::Mat& image) {
  for (int bx = 0; bx < coefficients.blocks_x; ++bx) {
    const std::int16_t* block = coefficients.Block(bx, by);
    float dequantized[64], pixels[64];
    for (int k = 0; k < 64; ++k) dequantized[k] = static_cast<float>(block[k]) * coefficients.quant[k];
    Transform(dequantized, pixels, true);
    for (int r = 0; r < 8; ++r) {
      float* row = image.ptr<float>(by * 8 + r) + bx * 8;
      for (int c = 0; c < 8; ++c) row[c] = pixels[r * 8 + c] + 128.0f;
    }
  }
}

cv::Mat PlainDecode(const JpegCoefficients& coefficients) {
  cv::Mat image(coefficients.blocks_y * 8, coefficients.blocks_x * 8, CV_32FC1);
#pragma omp parallel for schedule(static)
  for (int by = 0; by < coefficients.blocks_y; ++by) DecodeRowOfBlocks(coefficients, by, image);
  return image;
}

// ProjectOntoData for row `by` of blocks; returns how far its coefficients moved, summed over the row in order, when
// `measure` asks for it (0 otherwise). `bin_fraction` of each bin is allowed, centred (1: the whole bin). Built for
// AVX2 too, as DecodeRowOfBlocks.
__attribute__((target_clones("avx2", "default"))) double ProjectRowOfBlocks(const JpegCoefficients& coefficients,
                                                                            int by, cv::Mat& image, bool measure,
                                                                            float bin_fraction) {
  // Exactly 0.5 for the whole bin, and 0.5 q is exact, so the restoration's results are the same bit for bit.
  const float half_bin = bin_fraction * 0.5f;
  double moved = 0.0;
  for (int bx = 0; bx < coefficients.blocks_x; ++bx) {
    const std::int16_t* block = coefficients.Block(bx, by);
    float pixels[64], dct[64];
    for (int r = 0; r < 8; ++r) {
      const float* row = image.ptr<float>(by * 8 + r) + bx * 8;
      for (int c = 0; c < 8; ++c) pixels[r * 8 + c] = row[c] - 128.0f;
    }
    Transform(pixels, dct, false);
    float clamped[64];
    for (int k = 0; k < 64; ++k) {
      const float q = coefficients.quant[k], centre = static_cast<float>(block[k]) * q;
      clamped[k] = std::clamp(dct[k], centre - half_bin * q, centre + half_bin * q);
    }
    if (measure)
      for (int k = 0; k < 64; ++k) moved += std::abs(clamped[k] - dct[k]);
    Transform(clamped, pixels, true);
    for (int r = 0; r < 8; ++r) {
      float* row = image.ptr<float>(by * 8 + r) + bx * 8;
      for (int c = 0; c < 8; ++c) row[c] = std::clamp(pixels[r * 8 + c] + 128.0f, 0.0f, 255.0f);
    }
  }
  return moved;
}

// Moves every block's coefficients back into the quantization bins the file records (the central `bin_fraction` of
// each: ProjectOntoJpegBins), and every pixel into the 0..255 a decoder clamps to. Returns the mean distance the
// coefficients moved when `measure` asks for it (0 otherwise): summed in order in double precision, one chain of
// additions per row of blocks, that figure took most of the step's time, and only the last round's is reported.
double ProjectOntoData(const JpegCoefficients& coefficients, cv::Mat& image, bool measure, float bin_fraction) {
  // Per row of blocks, then added in order: the figure does not depend on the threads.
  std::vector<double> moved_per_row(static_cast<std::size_t>(coefficients.blocks_y), 0.0);
#pragma omp parallel for schedule(static)
  for (int by = 0; by < coefficients.blocks_y; ++by)
    moved_per_row[static_cast<std::size_t>(by)] = ProjectRowOfBlocks(coefficients, by, image, measure, bin_fraction);
  double moved = 0.0;
  for (double row : moved_per_row) moved += row;
  return moved / static_cast<double>(coefficients.indices.size());
}

// The three Bayer colour carriers as sign patterns: (-1)^(x+y) (green against red and blue), (-1)^x and (-1)^y (red
// against blue). The luminance sits at base band.
float CarrierSign(int carrier, int x, int y) {
  const int parity = carrier == 0 ? (x + y) : (carrier == 1 ? x : y);
  return (parity & 1) ? -1.0f : 1.0f;
}

// The narrow scale's filter: a Gaussian of `sigma`, then the three-tap binomial (1, 2, 1) / 4 along each axis. The
// binomial's zero at the Nyquist frequency is what makes it right for demodulated carriers: a carrier that alternates
// along one axis, (-1)^x or (-1)^y, turns the luminance into a signal at Nyquist along that axis, and a Gaussian alone
// passes some of it (2 exp(-pi^2 sigma^2 / 2): 1.4 % at sigma 1). The prior then took that share of the luminance out
// as if it were colour, twice a round (the two carriers), and every carrier's colour with it: the restored mosaic
// of the simulated leaves capture came out 1.25 codes darker than its truth (bright pixels 7.5), every block's mean at
// the low edge of its DC bin, and the views banded (BENCHMARKS.md, thirty-eighth session).
cv::Mat NarrowCarrierKernel(double sigma) {
  const cv::Mat gaussian = cv::getGaussianKernel(cvRound(sigma * 8 + 1) | 1, sigma, CV_32F);  // GaussianBlur's size
  cv::Mat kernel(gaussian.rows + 2, 1, CV_32F, cv::Scalar(0));
  for (int i = 0; i < gaussian.rows; ++i) {
    const float g = gaussian.at<float>(i);
    kernel.at<float>(i) += 0.25f * g;
    kernel.at<float>(i + 1) += 0.5f * g;
    kernel.at<float>(i + 2) += 0.25f * g;
  }
  return kernel;
}

// A Gaussian blur at a wide scale, computed on a grid `factor` times coarser (box-averaged down, bilinear back up):
// the same smooth result for a fraction of the cost of a kernel hundreds of taps long.
cv::Mat WideBlur(const cv::Mat& image, double sigma) {
  const int factor = std::max(1, static_cast<int>(sigma / 4.0));
  cv::Mat coarse, blurred, fine;
  cv::resize(image, coarse, cv::Size((image.cols + factor - 1) / factor, (image.rows + factor - 1) / factor), 0, 0,
             cv::INTER_AREA);
  cv::GaussianBlur(coarse, blurred, cv::Size(), sigma / factor, sigma / factor, cv::BORDER_REFLECT);
  cv::resize(blurred, fine, image.size(), 0, 0, cv::INTER_LINEAR);
  return fine;
}

// The prior step: takes out, around each carrier, what lies between the narrow and the wide scale (the colour the
// JPEG block pattern modulated, or zeroed block by block), leaving the scene's smooth colour and the luminance.
// Tried instead, and worse on both the simulated capture's fidelity and the real frames' bands: putting back the
// wide scale's colour per unit of brightness, times the pixel's brightness (a micro-image's colour follows its
// vignetting).
void SmoothCarrierColour(cv::Mat& image, double narrow_sigma, double wide_sigma) {
  const cv::Mat narrow_kernel = NarrowCarrierKernel(narrow_sigma);
  cv::Mat demodulated(image.size(), CV_32FC1), narrow;
  for (int carrier = 0; carrier < 3; ++carrier) {
#pragma omp parallel for schedule(static)
    for (int y = 0; y < image.rows; ++y) {
      const float* in = image.ptr<float>(y);
      float* out = demodulated.ptr<float>(y);
      for (int x = 0; x < image.cols; ++x) out[x] = in[x] * CarrierSign(carrier, x, y);
    }
    SeparableFilterInBands(demodulated, narrow, narrow_kernel, narrow_kernel, cv::BORDER_REFLECT);
    const cv::Mat wide = WideBlur(demodulated, wide_sigma);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < image.rows; ++y) {
      float* row = image.ptr<float>(y);
      const float* n = narrow.ptr<float>(y);
      const float* w = wide.ptr<float>(y);
      for (int x = 0; x < image.cols; ++x) row[x] -= CarrierSign(carrier, x, y) * (n[x] - w[x]);
    }
  }
}

// Whether the options' grey is the sensor's (every gain 1): then the mosaic is smoothed as it is, as it always was.
bool MeasuresColourFromSensorGrey(const MosaicRestoreOptions& options) {
  return std::all_of(options.grey_gains.begin(), options.grey_gains.end(), [](float g) { return g == 1.0f; });
}

// The mosaic in the space where the prior measures colour (MosaicRestoreOptions::grey_gains): (code - black) x gain
// per Bayer phase.
void ToGreyBalanced(cv::Mat& image, const MosaicRestoreOptions& options) {
  const float black = options.grey_black;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < image.rows; ++y) {
    float* row = image.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) row[x] = (row[x] - black) * options.grey_gains[BayerPhase(x, y)];
  }
}

// Back from ToGreyBalanced's space to codes.
void FromGreyBalanced(cv::Mat& image, const MosaicRestoreOptions& options) {
  const float black = options.grey_black;
#pragma omp parallel for schedule(static)
  for (int y = 0; y < image.rows; ++y) {
    float* row = image.ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) row[x] = row[x] / options.grey_gains[BayerPhase(x, y)] + black;
  }
}

// The prior step about the options' grey.
void SmoothColourAboutGrey(cv::Mat& image, const MosaicRestoreOptions& options) {
  if (MeasuresColourFromSensorGrey(options)) {
    SmoothCarrierColour(image, options.narrow_sigma, options.wide_sigma);
    return;
  }
  ToGreyBalanced(image, options);
  SmoothCarrierColour(image, options.narrow_sigma, options.wide_sigma);
  FromGreyBalanced(image, options);
}

// Into the 0..255 a decoder clamps to, in place (a matrix expression would allocate two more sensor-size images).
void ClampToCodes(cv::Mat& image) {
  cv::min(image, 255.0f, image);
  cv::max(image, 0.0f, image);
}

// The last step of the restoration: the prior once more after the last projection. That projection moves every
// block back into its own bins on its own, so the point of the bins nearest a smooth colour carries a clamp per block:
// the block pattern again, which the lens rows sample at a drifting phase (bands in the views). Ending on the prior
// leaves it out, at the price of the data's colour finer than the wide scale. Pixels the last projection left at full
// scale are clipped highlights and keep their value: the prior would tint them with the colour around, and the
// decoder neutralises clipped highlights by their level.
void EndOnThePrior(cv::Mat& image, const MosaicRestoreOptions& options) {
  constexpr float kFullScale = 254.5f;  // the projection clamps to 255; a clipped JPEG pixel decodes at 255
  CV_Assert(image.isContinuous());      // indexed as one run of pixels below
  std::vector<std::pair<std::size_t, float>> clipped;  // few (0.9 % of IMG_1): no copy of the whole image
  const float* pixels = image.ptr<float>();
  for (std::size_t i = 0; i < image.total(); ++i)
    if (pixels[i] >= kFullScale) clipped.emplace_back(i, pixels[i]);
  SmoothColourAboutGrey(image, options);
  for (const auto& [index, value] : clipped) image.ptr<float>()[index] = value;
  ClampToCodes(image);
}

// Refuses an image that is not float codes covering every block of the file: `what` names it in the message.
void RequireCodesCoveringBlocks(const cv::Mat& image, const JpegCoefficients& coefficients, const std::string& what) {
  if (image.type() == CV_32FC1 && image.cols == coefficients.blocks_x * 8 && image.rows == coefficients.blocks_y * 8)
    return;
  throw Error(what + " is " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
              (image.type() == CV_32FC1 ? " float" : " not float") + "; the file's " +
              std::to_string(coefficients.blocks_x) + " x " + std::to_string(coefficients.blocks_y) + " blocks need " +
              std::to_string(coefficients.blocks_x * 8) + " x " + std::to_string(coefficients.blocks_y * 8) +
              " float codes");
}

}  // namespace

std::optional<JpegCoefficients> ReadJpegCoefficients(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) ThrowFileError(name, "not a regular file");
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(name.c_str(), "rb"));
  if (!file) ThrowFileError(name, "cannot open");
  JpegCoefficients coefficients;
  std::string problem;
  switch (ReadCoefficientsInto(file.get(), name, coefficients, problem)) {
    case ReadOutcome::kRead:
      return coefficients;
    case ReadOutcome::kNotGreyscale:
      return std::nullopt;
    case ReadOutcome::kFailed:
      break;
  }
  ThrowFileError(name, "not a readable JPEG (" + problem + ")");
}

void ProjectOntoJpegBins(const JpegCoefficients& coefficients, cv::Mat& image, double bin_fraction) {
  RequireCodesCoveringBlocks(image, coefficients, "JPEG projection: the image");
  if (!(bin_fraction > 0.0 && bin_fraction <= 1.0))
    throw Error("JPEG projection: bin fraction " + std::to_string(bin_fraction) + " is outside (0, 1]");
  ProjectOntoData(coefficients, image, false, static_cast<float>(bin_fraction));
}

cv::Mat RestoreJpegMosaic(const JpegCoefficients& coefficients, const MosaicRestoreOptions& options,
                          MosaicRestoreReport* report) {
  if (options.iterations < 0 || !(options.narrow_sigma > 0.0) || !(options.wide_sigma > options.narrow_sigma))
    throw Error("JPEG mosaic restoration: need iterations >= 0 and 0 < narrow sigma < wide sigma");
  if (!std::all_of(options.grey_gains.begin(), options.grey_gains.end(),
                   [](float g) { return std::isfinite(g) && g > 0.0f; }) ||
      !std::isfinite(options.grey_black))
    throw Error("JPEG mosaic restoration: grey gains must be positive and the black level finite");
  const cv::Mat& start = options.start;
  if (!start.empty()) RequireCodesCoveringBlocks(start, coefficients, "JPEG mosaic restoration: the start");
  cv::Mat image = start.empty() ? PlainDecode(coefficients) : start.clone();
  // For the report's mean change only.
  const cv::Mat plain =
      options.iterations == 0 ? cv::Mat() : (start.empty() ? image.clone() : PlainDecode(coefficients));
  double last = 0.0;
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    SmoothColourAboutGrey(image, options);
    const bool last_round = iteration + 1 == options.iterations;
    const double moved = ProjectOntoData(coefficients, image, last_round, 1.0f);
    if (last_round) last = moved;
  }
  if (options.iterations > 0) {
    EndOnThePrior(image, options);
  } else {
    ClampToCodes(image);
  }
  if (report) {
    report->iterations = options.iterations;
    report->last_correction = last;
    report->mean_change = options.iterations > 0 ? cv::mean(cv::abs(image - plain))[0] : 0.0;
  }
  return image(cv::Rect(0, 0, coefficients.width, coefficients.height)).clone();
}

}  // namespace lfsp::decode
