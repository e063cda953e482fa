// Which grid estimator suits an image: centroids for white images, periodicity for captures.

#include <algorithm>
#include <cmath>
#include <vector>

#include "lattice.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

// Mean brightness in the central third of every usable lens's micro-image (every 3rd lens, for speed).
std::vector<double> LensBrightness(const cv::Mat& grey, const LensletGrid& grid) {
  std::vector<double> brightness;
  const double radius = grid.spacing_x / 6.0;
  const int r = static_cast<int>(std::ceil(radius));
  for (int j = 0; j < grid.rows; j += 3)
    for (int i = 0; i < grid.columns; i += 3) {
      double cx = 0.0, cy = 0.0;
      grid.Centre(i, j, cx, cy);
      const int x0 = static_cast<int>(std::lround(cx)), y0 = static_cast<int>(std::lround(cy));
      double sum = 0.0;
      int count = 0;
      for (int y = std::max(0, y0 - r); y <= std::min(grey.rows - 1, y0 + r); ++y)
        for (int x = std::max(0, x0 - r); x <= std::min(grey.cols - 1, x0 + r); ++x)
          if (std::hypot(x - cx, y - cy) <= radius) {
            sum += grey.at<float>(y, x);
            ++count;
          }
      if (count > 0) brightness.push_back(sum / count);
    }
  return brightness;
}

double Quantile(std::vector<double> values, double q) {
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(values.size() - 1));
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

bool EvenlyLit(const cv::Mat& grey, const LensletGrid& grid) {
  const std::vector<double> brightness = LensBrightness(grey, grid);
  if (brightness.size() < 16) return false;
  const double median = Quantile(brightness, 0.5);
  return median > 0.0 && Quantile(brightness, 0.05) >= median / 1.6 && Quantile(brightness, 0.95) <= median * 1.6;
}

// A centroid fit's starting point from a periodicity fit: its spacing, rotation and the lens nearest the axis.
GridGuess GuessFromGrid(const LensletGrid& grid, const std::optional<GridGuess>& guess) {
  GridGuess seeded;
  seeded.spacing = grid.spacing_x;
  seeded.scale_y = grid.spacing_y / (grid.spacing_x * kHalfSqrt3);
  seeded.rotation = grid.rotation;
  const double ax = guess && guess->axis_x > 0.0 ? guess->axis_x : 0.5 * (grid.sensor_width - 1);
  const double ay = guess && guess->axis_y > 0.0 ? guess->axis_y : 0.5 * (grid.sensor_height - 1);
  int i = 0, j = 0;
  grid.Nearest(ax, ay, i, j);
  grid.Centre(i, j, seeded.axis_x, seeded.axis_y);
  return seeded;
}

}  // namespace

std::string_view ToString(LensletImageKind kind) {
  switch (kind) {
    case LensletImageKind::kAuto:
      return "auto";
    case LensletImageKind::kWhiteImage:
      return "white";
    case LensletImageKind::kCapture:
      return "capture";
  }
  return "?";
}

LensletImageKind LensletImageKindFromString(const std::string& name) {
  for (const LensletImageKind kind :
       {LensletImageKind::kAuto, LensletImageKind::kWhiteImage, LensletImageKind::kCapture})
    if (ToString(kind) == name) return kind;
  throw Error("image kind '" + name + "': unknown (expected auto, white or capture)");
}

GridEstimate FindLensletGrid(const cv::Mat& grey, const std::optional<GridGuess>& guess, LensletImageKind kind) {
  if (kind == LensletImageKind::kWhiteImage && guess && guess->spacing > 0.0) return EstimateLensletGrid(grey, *guess);
  GridEstimate periodic = EstimateLensletGridFromCapture(grey, guess);
  if (kind == LensletImageKind::kCapture) return periodic;
  if (kind == LensletImageKind::kAuto && !EvenlyLit(grey, periodic.grid)) return periodic;
  return EstimateLensletGrid(grey, GuessFromGrid(periodic.grid, guess));
}

GridEstimate FindLensletGridInCapture(const RawImage& capture, const LytroMetadata& metadata) {
  const cv::Mat grey = WhiteImageToGrey(capture, metadata.RequireRawFormat(), metadata.source);
  std::optional<GridGuess> guess;
  if (metadata.mla) guess = GuessFromMetadata(metadata, capture.width, capture.height);
  return FindLensletGrid(grey, guess, LensletImageKind::kCapture);
}

}  // namespace lfsp::decode
