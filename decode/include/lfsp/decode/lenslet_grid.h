#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/core/hex_lattice.h"
#include "lfsp/decode/lytro_metadata.h"
#include "lfsp/decode/raw_packing.h"

namespace lfsp::decode {

// The micro-lens lattice of a camera on its sensor: the hexagonal geometry (lfsp::HexLattice, shared with the
// simulator's camera model, so a fitted grid compares with the truth term by term) and the usable lenses.
// Lens (0, 0) is the top-left lens of the usable grid (every lens 0 <= i < columns, 0 <= j < rows has its whole
// micro-image, radius spacing_x / 2, on the sensor).
struct LensletGrid : HexLattice {
  int columns = 0;
  int rows = 0;
  int sensor_width = 0;
  int sensor_height = 0;

  // How the grid was found and how well it fits (empty / zero for a grid that was not fitted).
  std::string fit_method;     // "white-image centroids" or "capture periodicity"
  double rms_residual = 0.0;  // px: RMS distance of the inlier centroids (white image) or of the blocks' local
                              // lattice positions (capture) from the fitted lattice
  int lenses_measured = 0;    // white image: micro-images whose centroid was measured
  int lenses_used = 0;        // white image: inliers of the final fit
  int blocks = 0;             // capture: blocks of about 12 x 12 lenses whose lattice phase was measured
  int blocks_used = 0;        // capture: inlier blocks of the final fit

  nlohmann::json ToJson() const;
  // lfsp::Error naming `source` if a field is missing or out of range.
  static LensletGrid FromJson(const nlohmann::json& json, const std::string& source);
};

// RMS distance of a grid's lens centres from a reference lattice's, over the reference's lenses 0 <= i < columns,
// 0 <= j < rows: how far a fitted grid lies from the truth. `Reference` is any lattice with `rows`, `columns` and a
// `Centre(i, j)` returning a point with `x` and `y` (the simulator's LensletLattice, which decode does not link).
template <class Reference>
double CentreRmsFrom(const LensletGrid& grid, const Reference& reference) {
  double sum = 0.0;
  for (int j = 0; j < reference.rows; ++j)
    for (int i = 0; i < reference.columns; ++i) {
      double x = 0.0, y = 0.0;
      grid.Centre(i, j, x, y);
      const auto truth = reference.Centre(i, j);
      sum += (x - truth.x) * (x - truth.x) + (y - truth.y) * (y - truth.y);
    }
  return reference.rows * reference.columns > 0 ? std::sqrt(sum / (reference.rows * reference.columns)) : 0.0;
}

// Which micro-lens each sensor pixel lies under, as a label that differs between any two neighbouring lenses
// ((i mod 4) + 4 (j mod 2), CV_8U): enough to keep an interpolation within one micro-image. Parallel.
cv::Mat LensLabels(const LensletGrid& grid);

// Where the estimation starts: the camera's description of its micro-lens array.
struct GridGuess {
  double spacing = 0.0;   // px along a row (lensPitch / pixelPitch * scaleFactor.x)
  double scale_y = 1.0;   // row spacing = spacing * sqrt(3)/2 * scale_y
  double rotation = 0.0;  // rad, in the lattice convention above
  double axis_x = 0.0;    // px: where the lens nearest the optical axis sits (sensor centre minus sensorOffset)
  double axis_y = 0.0;
};

// The guess a camera's metadata gives (devices.mla.* and devices.sensor.pixelPitch) for a sensor of that size.
// lfsp::Error naming the metadata source if the micro-lens description is missing.
GridGuess GuessFromMetadata(const LytroMetadata& metadata, int sensor_width, int sensor_height);

struct GridEstimateOptions {
  double window_radius = 0.4;    // centroid window radius as a fraction of the spacing (stays inside the disc)
  int centroid_iterations = 5;   // re-centred intensity-weighted centroid iterations per micro-image
  double min_brightness = 0.3;   // micro-images dimmer than this fraction of the median are not used
  double outlier_sigmas = 4.0;   // centroids further than this many robust sigmas from the fit are outliers
  double min_outlier_px = 0.05;  // ... but never call a centroid within this distance an outlier
};

// One measured micro-image centre, lattice-indexed as in the final grid (indices may be outside the usable range).
struct MeasuredCentre {
  int i = 0;
  int j = 0;
  double x = 0.0;
  double y = 0.0;
  bool inlier = false;
};

struct GridEstimate {
  LensletGrid grid;
  std::vector<MeasuredCentre> centres;
};

// A white image as one grey float image for grid fitting and devignetting: levels from the raw format, each of the
// four Bayer phases divided by its own mean (so the sensor's colour response leaves no checkerboard), then scaled so
// that the 99.9th percentile (the micro-image centres) is 1.
cv::Mat WhiteImageToGrey(const RawImage& white, const RawFormat& format, const std::string& source);

// Fits the lattice to a grey white image: sub-pixel centroid of every micro-image (re-centred, smoothly windowed,
// intensity-weighted), then a least-squares fit of spacing x/y, rotation and origin over all of them, grown from the
// optical axis outwards and robust to outliers (dim vignetted border lenses, defects). lfsp::Error if the image does
// not show a lattice near the guess.
GridEstimate EstimateLensletGrid(const cv::Mat& grey_white, const GridGuess& guess,
                                 const GridEstimateOptions& options = {});

// The grid a decode fits on a white image: EstimateLensletGrid with default options from GuessFromMetadata of
// `mla_source` (the white image's own micro-lens description, else the capture's) for a sensor of grey_white's size.
// The one recipe the decode and the white-image database's stored grids share, so a stored grid is the fitted one.
GridEstimate FitGridOnWhiteImage(const cv::Mat& grey_white, const LytroMetadata& mla_source);

// Fits the lattice to any lenslet image, including an ordinary capture (scene content, dark and saturated regions,
// JPEG blocking, vignetted corners), from its periodicity: the spectral peaks of the image's local contrast (its dark
// side, the gaps and rims that the micro-lenses' edges fix) give the lattice vectors, the lattice phase of every block
// of about 12 x 12 lenses (fitted as a plane over the sensor) refines them and gives the lattice position, averaged
// over the whole sensor. `guess`, when given, bounds the spacing search to +-15 % of guess->spacing (> 0), picks the
// row direction nearest guess->rotation and indexes lenses from guess->axis; without it, spacings of 4 px to 60 px (or
// a sixth of the image) are searched, rows are taken nearest horizontal and the axis is the image centre. `grey` as
// WhiteImageToGrey makes it. The result has no per-lens centres. lfsp::Error if the image shows no lattice.
GridEstimate EstimateLensletGridFromCapture(const cv::Mat& grey, const std::optional<GridGuess>& guess);

// What a lenslet image is, for choosing how to fit its grid.
enum class LensletImageKind {
  kAuto,        // decide from the image: micro-images of even brightness are a white image
  kWhiteImage,  // per-lens centroids (EstimateLensletGrid), seeded by the periodicity fit when there is no guess
  kCapture,     // periodicity only (EstimateLensletGridFromCapture)
};
std::string_view ToString(LensletImageKind kind);
LensletImageKind LensletImageKindFromString(const std::string& name);  // auto | white | capture

// The lattice of any grey lenslet image (WhiteImageToGrey of a white image or a capture). kAuto fits by
// periodicity, then refines by centroids when the micro-images are evenly lit (90 % of the lenses within a factor
// of 1.6 of the median brightness): centroids are the more precise where the scene does not pull them.
GridEstimate FindLensletGrid(const cv::Mat& grey, const std::optional<GridGuess>& guess, LensletImageKind kind);

// The lattice of a raw capture by periodicity (kCapture), levelled by its raw format and started from its micro-lens
// description when the metadata has one.
GridEstimate FindLensletGridInCapture(const RawImage& capture, const LytroMetadata& metadata);

}  // namespace lfsp::decode
