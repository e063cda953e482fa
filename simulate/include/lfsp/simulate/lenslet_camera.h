#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "lfsp/core/conventions.h"
#include "lfsp/core/hex_lattice.h"

namespace lfsp::simulate {

// One white-image calibration point: the lens zoom/focus step and the exit-pupil distance at that zoom.
struct LensSetting {
  int zoom_step = 0;
  int focus_step = 0;
  double exit_pupil = 10000.0;  // m (devices.lens.exitPupilOffset.z); 10000 = effectively at infinity (F01)
};

// A Lytro-like lenslet camera: sensor, hexagonal micro-lens array, main lens, colour and noise. Values of the
// presets are taken from real metadata (../shared/data/lytro): F01 frame metadata, the Illum LFR and white image.
struct CameraModel {
  std::string name;         // "f01", "illum", "mini-illum"
  std::string model;        // camera.model in the frame metadata: "F01" or "ILLUM"
  std::string white_model;  // camera.model in white-image TXT files: "F01" or "B01"
  std::string firmware;
  std::string serial;  // privateMetadata.camera.serialNumber
  std::string sensor_serial;

  // Sensor.
  int sensor_width = 0;
  int sensor_height = 0;
  double pixel_pitch = 1.4e-6;  // m
  int bits = 10;                // 12 (F01, big-endian packing) or 10 (Illum packing)
  std::string bayer = "grbg";   // top-left 2x2 tile, row by row: "bggr" (F01) or "grbg" (Illum)
  int black = 64;
  int white = 1023;
  double response_r = 0.757;  // sensor response relative to green (devices.sensor.normalizedResponses)
  double response_b = 0.722;
  // The colour matrix the capture's metadata gives (image.color.ccm / ccmRgbToSrgbArray, row-major, applied to
  // white-balanced sensor RGB). The sensor is rendered through its inverse, so a decoder that applies the metadata
  // gets the scene's colours back.
  std::array<double, 9> ccm = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int iso = 100;

  // Micro-lens array (devices.mla).
  double lens_pitch = 2e-5;      // m
  double rotation = 0.0;         // rad, lattice row direction (cos, sin) in image coordinates (y down)
  double scale_x = 1.0;          // scaleFactor.x
  double scale_y = 1.0;          // scaleFactor.y: row spacing is pitch * sqrt(3)/2 * scale_y
  double sensor_offset_x = 0.0;  // m, from the micro-lens nearest the optical axis to the sensor centre
  double sensor_offset_y = 0.0;
  double sensor_offset_z = 3.7e-5;  // m, MLA to sensor distance
  int row_shift = 0;                // which lens rows are shifted by half a pitch: rows with (j + row_shift) odd

  // Main lens.
  double f_number = 2.0;
  double mla_f_number = 2.0;  // micro-lens f-number; discs fill the pitch when the main lens matches it
  double focal_length = 0.0139;
  double infinity_lambda = 15.4;
  std::vector<LensSetting> white_settings;  // white images to write (MOD_0000, MOD_0001, ...)
  int capture_setting = 0;                  // which of them the capture was taken at (same zoom/focus)

  // Noise and exposure.
  double full_well = 9000.0;        // electrons at the white level
  double read_noise = 1.5;          // DN (standard deviation)
  double exposure_duration = 0.04;  // s, written as devices.shutter.frameExposureDuration
  double modulation_exposure_bias = 0.245;

  // Derived values.
  double SpacingPixels(const LensSetting& setting) const;  // horizontal centre spacing at that zoom
  double DiscRadius(const LensSetting& setting) const;     // micro-image radius in pixels (aperture-limited)
  // Row c: what sensor channel c (before its response) records of scene-linear RGB: the inverse of `ccm`.
  std::array<double, 9> SceneToSensor() const;
};

// "f01", "illum", "mini-illum" or "mini-f01" (Illum / F01 optics on a small sensor, for fast tests and samples).
// lfsp::Error if unknown.
CameraModel CameraPreset(const std::string& name);
std::vector<std::string> CameraPresetNames();

// The hexagonal lattice of micro-image centres on the sensor, in pixels (pixel centres at integers).
//   centre(i, j) = origin + R(rotation) * ((i + shift(j)/2) * spacing, j * spacing * sqrt(3)/2 * scale_y),
//   shift(j) = (j + row_shift) & 1.
// Lens (0, 0) is the top-left lens of the usable grid; `columns` x `rows` lenses all have their whole micro-image
// (radius spacing/2) inside the sensor. The geometry is lfsp::HexLattice's (Geometry()), the one the decoder fits;
// this form keeps the camera's own terms (a pitch and a vertical scale).
struct LensletLattice {
  double spacing = 0;
  double scale_y = 1;
  double rotation = 0;
  double origin_x = 0;
  double origin_y = 0;
  int row_shift = 0;
  int columns = 0;
  int rows = 0;

  double RowSpacing() const;
  HexLattice Geometry() const;
  int Shift(int j) const { return HexLattice{.row_shift = row_shift}.Shift(j); }
  PixelPosition Centre(int i, int j) const;
  // Lattice-frame offset (along the row, across the rows) of a sensor point from lens (i, j)'s centre.
  void LocalOffset(double x, double y, int i, int j, double& along, double& across) const;
  // The lens whose centre is nearest to sensor point (x, y) (indices may fall outside [0, columns) x [0, rows)).
  void Nearest(double x, double y, int& i, int& j) const;
};

// The lattice of a camera at one lens setting: spacing grows with 1 + z/exit_pupil (micro-images are projections
// of the exit pupil), centred on the sensor centre minus the sensor offset.
LensletLattice MakeLattice(const CameraModel& camera, const LensSetting& setting);

// The decoded (hex -> rect) grid: decoded pixel (x, y) sits at lattice position a = x * sqrt(3)/2 lens pitches
// along the row, row y; width = floor((columns - 1) * 2/sqrt(3)) + 1, height = rows.
// The view count and step follow LFToolbox: n = even(ceil(spacing)), views = n - 1 (Illum 15, F01 9), one view
// step = spacing / n sensor pixels, isotropic (view (u, v) samples the lattice-frame offset ((u-uc), (v-vc)) * step).
struct DecodedGrid {
  int views = 15;
  double view_step = 0;
  int width = 0;
  int height = 0;
};
DecodedGrid MakeDecodedGrid(const CameraModel& camera, const LensletLattice& lattice);

}  // namespace lfsp::simulate
