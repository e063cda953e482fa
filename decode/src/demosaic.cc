#include "lfsp/decode/demosaic.h"

#include <omp.h>

#include <algorithm>
#include <initializer_list>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <utility>

#include "bayer_levels.h"
#include "lfsp/core/error.h"

namespace lfsp::decode {
namespace {

// OpenCV names a Bayer pattern by the second row's second and third pixels, so its names are the "opposite" of the
// top-left tile: an RGGB sensor is COLOR_BayerBG.
int OpenCvCode(BayerPattern pattern, bool edge_aware) {
  switch (pattern) {
    case BayerPattern::kRGGB:
      return edge_aware ? cv::COLOR_BayerBG2RGB_EA : cv::COLOR_BayerBG2RGB;
    case BayerPattern::kGRBG:
      return edge_aware ? cv::COLOR_BayerGB2RGB_EA : cv::COLOR_BayerGB2RGB;
    case BayerPattern::kGBRG:
      return edge_aware ? cv::COLOR_BayerGR2RGB_EA : cv::COLOR_BayerGR2RGB;
    case BayerPattern::kBGGR:
      return edge_aware ? cv::COLOR_BayerRG2RGB_EA : cv::COLOR_BayerRG2RGB;
  }
  return cv::COLOR_BayerBG2RGB;
}

cv::Mat DemosaicOpenCv(const cv::Mat& bayer, BayerPattern pattern, bool edge_aware, float max_value) {
  const double scale = 65535.0 / max_value;
  cv::Mat sixteen;
  bayer.convertTo(sixteen, CV_16U, scale);  // saturates above max_value
  cv::Mat rgb16;
  cv::demosaicing(sixteen, rgb16, OpenCvCode(pattern, edge_aware));
  cv::Mat rgb;
  rgb16.convertTo(rgb, CV_32F, 1.0 / scale);
  return rgb;
}

// Malvar's 5x5 correction is used where the white image stays at or above this over the whole window. Beyond, its
// taps reach the dark gap between micro-images and the neighbouring lens's micro-image: dividing by the small white
// there amplifies that neighbour's content, and the outermost well-lit Illum views (weight 0.64) came out displaced
// outward by 0.28 px (bilinear's 3x3 taps: 0.03 px).
constexpr float kGradientMinWhite = 0.15f;

// Mirrors an index about the first / last pixel (keeps the Bayer phase: reflecting by 2k is phase-preserving).
inline int Reflect(int i, int n) { return i < 0 ? -i : (i >= n ? 2 * n - 2 - i : i); }

// Malvar-He-Cutler: bilinear interpolation corrected by the Laplacian of the known channel (5x5 kernels).
// Row pointers r[0..4] hold rows y-2..y+2; xm2..xp2 the columns x-2..x+2 (mirrored at the borders).
inline void GradientPixel(const float* const* r, int x, int xm2, int xm1, int xp1, int xp2, int colour,
                          int horizontal_colour, float* out) {
  const float c = r[2][x];
  const float axial = r[1][x] + r[3][x] + r[2][xm1] + r[2][xp1];
  const float axial2 = r[0][x] + r[4][x] + r[2][xm2] + r[2][xp2];
  const float diagonal = r[1][xm1] + r[1][xp1] + r[3][xm1] + r[3][xp1];
  float red = 0.0f, green = 0.0f, blue = 0.0f;
  if (colour == 1) {
    green = c;
    // Green pixel: one of red/blue lies left-right, the other up-down.
    const float horizontal =
        (5.0f * c + 4.0f * (r[2][xm1] + r[2][xp1]) - (r[2][xm2] + r[2][xp2]) - diagonal + 0.5f * (r[0][x] + r[4][x])) *
        0.125f;
    const float vertical =
        (5.0f * c + 4.0f * (r[1][x] + r[3][x]) - (r[0][x] + r[4][x]) - diagonal + 0.5f * (r[2][xm2] + r[2][xp2])) *
        0.125f;
    red = horizontal_colour == 0 ? horizontal : vertical;
    blue = horizontal_colour == 0 ? vertical : horizontal;
  } else {
    green = (4.0f * c + 2.0f * axial - axial2) * 0.125f;
    const float opposite = (6.0f * c + 2.0f * diagonal - 1.5f * axial2) * 0.125f;
    red = colour == 0 ? c : opposite;
    blue = colour == 0 ? opposite : c;
  }
  out[0] = red;
  out[1] = green;
  out[2] = blue;
}

// Interpolation near a micro-image's edge, from the neighbours under the same micro-lens as the pixel: those across
// the gap belong to another micro-image, which sees another part of the scene. Rows r[0..4] and lens labels
// l[0..4] hold rows y-2..y+2, column[0..4] the columns x-2..x+2.
//
// A missing channel comes from pairs of neighbours on opposite sides of the pixel. A pair wholly under the lens
// gives its mean. Where the outer one is missing, the inner one's value alone stands for a point a pixel further
// in, that is, for another view: taken as it was, it made the F01's outer views ((8, 4), 4 view steps out) read as
// if sampled a third of a view step towards the centre. So the one-sided estimate adds the pixel's own channel's
// change from two pixels in (colour differences vary slowly: C(p) - K(p) = C(q) - K(q), with K(q) the mean of K(p)
// and K two pixels in); where that pixel is under another lens too, the inner neighbour's value stands alone.
//
// A one-sided estimate is exact for a linear signal, but not symmetric about the pixel: on a texture it lags by a
// fraction of its period, more for finer texture. In a micro-image the texture is finer the farther the scene lies
// from the focal plane, so the outer views read |disparity| too small (the F01's corner views of the central 7 x 7,
// 4.2 px out, read 1-1.7 % of their offset inwards; every strip of e2e/full_size 0.5 % closer to d = 0; issue 49).
// So where one of the pairs is wholly under the lens, the complete pairs alone give the estimate; the one-sided
// estimates only stand in where no pair is complete.
class EdgeWindow {
 public:
  EdgeWindow(const float* const* r, const std::uint8_t* const* l, const int* column, bool green_centre)
      : r_(r), l_(l), column_(column), lens_(l[2][column[2]]), green_centre_(green_centre) {}

  // The estimate from the one neighbour q of the pair at +-(dy, dx) that is under the lens, or nullopt when neither
  // is (called for incomplete pairs): C(q) + K(p) - K(q), K being the pixel's own channel. K(q) is the mean of K
  // on both sides of q across the pair's direction where both are under the lens (exact for a texture that varies
  // along the pair only, at any fineness, as beside a boundary across the pair); else the mean of K(p) and K two
  // pixels in (exact only for a linear signal).
  [[gnu::always_inline]] std::optional<float> OneSided(int dy, int dx) const {
    const bool ahead = Inside(dy, dx), behind = Inside(-dy, -dx);
    if (!ahead && !behind) return std::nullopt;
    const int s = ahead ? 1 : -1, qy = s * dy, qx = s * dx;
    const int ay = qy + dx, ax = qx - dy, by = qy - dx, bx = qx + dy;  // q's neighbours across the direction
    if (SameChannel(ay, ax) && Inside(ay, ax) && Inside(by, bx))
      return At(qy, qx) + At(0, 0) - 0.5f * (At(ay, ax) + At(by, bx));
    if (Inside(2 * qy, 2 * qx)) return At(qy, qx) + 0.5f * (At(0, 0) - At(2 * qy, 2 * qx));
    return At(qy, qx);
  }

  // The mean of the complete pairs' means; without a complete pair, the mean of the one-sided estimates; with no
  // neighbour under the lens, the plain mean of all of them.
  [[gnu::always_inline]] float Mean(std::initializer_list<std::pair<int, int>> directions) const {
    float complete = 0.0f, one_sided = 0.0f, all = 0.0f;
    int complete_count = 0, one_sided_count = 0;
    for (const auto& [dy, dx] : directions) {
      all += At(dy, dx) + At(-dy, -dx);
      if (Inside(dy, dx) && Inside(-dy, -dx)) {
        complete += 0.5f * (At(dy, dx) + At(-dy, -dx));
        ++complete_count;
      } else if (const std::optional<float> estimate = OneSided(dy, dx)) {
        one_sided += *estimate;
        ++one_sided_count;
      }
    }
    if (complete_count > 0) return complete / static_cast<float>(complete_count);
    if (one_sided_count > 0) return one_sided / static_cast<float>(one_sided_count);
    return all / static_cast<float>(2 * directions.size());
  }

  float Centre() const { return At(0, 0); }

 private:
  bool Inside(int dy, int dx) const { return l_[2 + dy][column_[2 + dx]] == lens_; }
  // Whether the pixel at (dy, dx) has the centre pixel's colour filter (green: every other pixel on the diagonals).
  bool SameChannel(int dy, int dx) const {
    return green_centre_ ? ((dy + dx) & 1) == 0 : ((dy & 1) == 0 && (dx & 1) == 0);
  }
  float At(int dy, int dx) const { return r_[2 + dy][column_[2 + dx]]; }

  const float* const* r_;
  const std::uint8_t* const* l_;
  const int* column_;
  std::uint8_t lens_;
  bool green_centre_;
};

inline void EdgePixel(const EdgeWindow& e, int colour, int horizontal_colour, float* out) {
  const float c = e.Centre();
  float red = 0.0f, green = 0.0f, blue = 0.0f;
  if (colour == 1) {
    green = c;
    const float horizontal = e.Mean({{0, 1}});
    const float vertical = e.Mean({{1, 0}});
    red = horizontal_colour == 0 ? horizontal : vertical;
    blue = horizontal_colour == 0 ? vertical : horizontal;
  } else {
    green = e.Mean({{0, 1}, {1, 0}});
    const float opposite = e.Mean({{1, 1}, {1, -1}});
    red = colour == 0 ? c : opposite;
    blue = colour == 0 ? opposite : c;
  }
  out[0] = red;
  out[1] = green;
  out[2] = blue;
}

// Pixels whose 5x5 window lies wholly inside one micro-image: under a single lens, and lit by the white image at
// or above `min_white` everywhere in it. Computed by bands of rows (each read with the window's 2 rows beyond it),
// so the filters' sensor-size temporaries (an Illum's 371 MB) are never held at once beside the demosaic's output.
cv::Mat InsideMicroImages(const MicroImages& micro_images, float min_white) {
  constexpr int kBandRows = 256;
  constexpr int kReach = 2;  // the window's half size
  const cv::Mat window = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * kReach + 1, 2 * kReach + 1));
  const int rows = micro_images.white_grey.rows;
  cv::Mat inside(rows, micro_images.white_grey.cols, CV_8UC1);
  for (int first = 0; first < rows; first += kBandRows) {
    const int last = std::min(rows, first + kBandRows);
    const cv::Range read(std::max(0, first - kReach), std::min(rows, last + kReach));
    const cv::Range kept(first - read.start, last - read.start);
    // BORDER_ISOLATED: the band's own edges count as the image's; the rows kept lie kReach inside them.
    cv::Mat darkest, lowest_label, highest_label;
    cv::erode(micro_images.white_grey.rowRange(read), darkest, window, cv::Point(-1, -1), 1,
              cv::BORDER_CONSTANT | cv::BORDER_ISOLATED);
    cv::erode(micro_images.lens_labels.rowRange(read), lowest_label, window, cv::Point(-1, -1), 1,
              cv::BORDER_CONSTANT | cv::BORDER_ISOLATED);
    cv::dilate(micro_images.lens_labels.rowRange(read), highest_label, window, cv::Point(-1, -1), 1,
               cv::BORDER_CONSTANT | cv::BORDER_ISOLATED);
    const cv::Mat band =
        (darkest.rowRange(kept) >= min_white) & (lowest_label.rowRange(kept) == highest_label.rowRange(kept));
    band.copyTo(inside.rowRange(first, last));
  }
  return inside;
}

cv::Mat DemosaicGradient(const cv::Mat& bayer, BayerPattern pattern, const MicroImages* micro_images) {
  const std::array<int, 4> tile = TileColours(pattern);
  const int rows = bayer.rows, cols = bayer.cols;
  const cv::Mat inside = micro_images ? InsideMicroImages(*micro_images, kGradientMinWhite) : cv::Mat();
  cv::Mat rgb(rows, cols, CV_32FC3);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < rows; ++y) {
    const float* r[5];
    const std::uint8_t* l[5] = {nullptr, nullptr, nullptr, nullptr, nullptr};
    for (int d = -2; d <= 2; ++d) {
      r[d + 2] = bayer.ptr<float>(Reflect(y + d, rows));
      if (micro_images) l[d + 2] = micro_images->lens_labels.ptr<std::uint8_t>(Reflect(y + d, rows));
    }
    float* out = rgb.ptr<float>(y);
    const std::uint8_t* use_gradient = inside.empty() ? nullptr : inside.ptr<std::uint8_t>(y);
    const int even = tile[static_cast<std::size_t>(2 * (y & 1))], odd = tile[static_cast<std::size_t>(2 * (y & 1) + 1)];
    auto pixel = [&](int x, int xm2, int xm1, int xp1, int xp2) {
      const int colour = (x & 1) ? odd : even, horizontal_colour = (x & 1) ? even : odd;
      if (use_gradient == nullptr || use_gradient[x] != 0)
        GradientPixel(r, x, xm2, xm1, xp1, xp2, colour, horizontal_colour, out + 3 * x);
      else {
        const int column[5] = {xm2, xm1, x, xp1, xp2};
        EdgePixel(EdgeWindow(r, l, column, colour == 1), colour, horizontal_colour, out + 3 * x);
      }
    };
    auto border = [&](int x) {
      pixel(x, Reflect(x - 2, cols), Reflect(x - 1, cols), Reflect(x + 1, cols), Reflect(x + 2, cols));
    };
    border(0);
    border(1);
    for (int x = 2; x + 2 < cols; ++x) pixel(x, x - 2, x - 1, x + 1, x + 2);
    for (int x = std::max(2, cols - 2); x < cols; ++x) border(x);
  }
  return rgb;
}

}  // namespace

std::string_view ToString(DemosaicMethod method) {
  switch (method) {
    case DemosaicMethod::kBilinear:
      return "bilinear";
    case DemosaicMethod::kEdgeAware:
      return "edge-aware";
    case DemosaicMethod::kGradient:
      return "gradient";
  }
  return "?";
}

DemosaicMethod DemosaicMethodFromString(const std::string& name) {
  for (const DemosaicMethod method : {DemosaicMethod::kBilinear, DemosaicMethod::kEdgeAware, DemosaicMethod::kGradient})
    if (name == ToString(method)) return method;
  throw Error("demosaic method '" + name + "': unknown (expected bilinear, edge-aware or gradient)");
}

cv::Mat Demosaic(const cv::Mat& bayer, BayerPattern pattern, DemosaicMethod method, float max_value,
                 const MicroImages* micro_images) {
  if (bayer.type() != CV_32FC1 || bayer.rows < 4 || bayer.cols < 4)
    throw Error("demosaic: expected a single-channel float Bayer image of at least 4x4 pixels");
  switch (method) {
    case DemosaicMethod::kBilinear:
      return DemosaicOpenCv(bayer, pattern, false, max_value);
    case DemosaicMethod::kEdgeAware:
      return DemosaicOpenCv(bayer, pattern, true, max_value);
    case DemosaicMethod::kGradient:
      return DemosaicGradient(bayer, pattern, micro_images);
  }
  throw Error("demosaic: unknown method");
}

}  // namespace lfsp::decode
