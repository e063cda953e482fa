#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::depth {

// A frequency of a 2-D map, cycles per pixel along x (columns) and y (rows), each in [-0.5, 0.5).
struct MapFrequency {
  double fx = 0.0;
  double fy = 0.0;
};

// Where a pattern tied to the lens lattice can show in the views of a lenslet decode (decode/lenslet_decoder.h,
// DecodedGeometry: one view row per lens row, x * sqrt(3)/2 lens pitches along it). A view samples every lens once,
// so anything the same under every lens is constant in the views; a lattice shows only where the lenses beat with
// something else fixed to the sensor. Listed: every harmonic (m, n), |m|, |n| <= 4, of a pattern of period 8 px
// in x and y (the blocks of a JPEG mosaic; its harmonics m, n = 4 are the 2 x 2 Bayer tile's), sampled at the lens
// centres and carried into the view's pixels; and the decoder's own, the alternation of shifted and unshifted lens
// rows (0, 1/2) and the phase of the cubic interpolation along a row, which cycles every 1 / (1 - sqrt(3)/2) = 7.5 px
// and is half a cycle apart on the two row parities ((1 - sqrt(3)/2, 1/2) and its second harmonic). `spacing_x` is the
// lens pitch along a row, `spacing_y` the distance between rows (px), `rotation` the rows' angle (rad).
std::vector<MapFrequency> LensLatticeFrequencies(double spacing_x, double spacing_y, double rotation);

// The same from a light field's metadata (the decoder's "decode" section: grid_spacing_x, grid_spacing_y,
// grid_rotation); none for a light field that was not decoded from a lenslet sensor.
std::optional<std::vector<MapFrequency>> LensLatticeFrequencies(const LightField& light_field);

// The strongest of those frequencies in a map (disparity, confidence), as a power ratio: the map's power spectrum is
// averaged over 64 x 64 blocks that overlap by half, inside a 15 px frame left out as the HCI metrics leave it
// (Hann-windowed, each about its own mean; Welch's method, so that
// the spectrum of noise is smooth), and each frequency's power is divided by the larger of two medians around it: of
// the 7 x 7 bins around it, and of the bins 2-4 bins nearer to and farther from zero frequency along its radius. A
// periodic pattern is a point in the spectrum and stands above both; the edges of a scene and the streaks semi-global
// aggregation leaves along its eight paths put lines through zero frequency, which the radial median follows. Noise
// reads about 1; a lattice visible in a map reads several times that. Non-finite samples count as the map's mean.
struct LatticePeak {
  double ratio = 0.0;  // 0 when no frequency lies outside the lowest 2.5 bins
  MapFrequency frequency;
};
// Nothing for a map of fewer than two blocks and the frame (158 px) down or across, such as the bundled samples' views.
std::optional<LatticePeak> StrongestLatticePeak(const cv::Mat& map, const std::vector<MapFrequency>& frequencies);

nlohmann::ordered_json ToJson(const LatticePeak& peak);

}  // namespace lfsp::depth
