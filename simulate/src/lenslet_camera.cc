#include "lfsp/simulate/lenslet_camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lfsp/core/error.h"
#include "lfsp/decode/raw_input.h"

namespace lfsp::simulate {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

// The sensor, micro-lens and colour facts that decode also uses for raw images without metadata (one copy, in
// decode::NominalCameraFacts, from the real files).
void ApplyCameraFacts(const decode::CameraFacts& facts, CameraModel& c) {
  c.pixel_pitch = facts.pixel_pitch;
  c.bits = facts.bits;
  c.bayer = decode::ToString(facts.mosaic) == "BGGR" ? "bggr" : "grbg";
  c.black = static_cast<int>(facts.black);
  c.white = static_cast<int>(facts.white);
  c.ccm = facts.ccm;
  c.lens_pitch = facts.lens_pitch;
  c.rotation = facts.rotation;
  c.scale_x = 1.0;
  c.scale_y = facts.scale_y;
  if (facts.normalized_response) {
    c.response_r = facts.normalized_response->r;
    c.response_b = facts.normalized_response->b;
  } else {
    // The inverse of the white-balance gains, relative to green.
    c.response_r = facts.white_balance.gr / facts.white_balance.r;
    c.response_b = facts.white_balance.gr / facts.white_balance.b;
  }
}

// Values from the real Illum LFR (../shared/data/lytro/illum_demo.LFP) and Illum white-image TXT.
CameraModel IllumOptics() {
  CameraModel c;
  ApplyCameraFacts(decode::NominalCameraFacts("illum", "camera preset"), c);
  c.model = "ILLUM";
  c.white_model = "B01";
  c.firmware = "1.1.0 (31)";
  c.serial = "B5151500001";
  c.sensor_serial = "0B320406";
  c.iso = 122;
  c.sensor_offset_x = 1.440673828125e-06;
  c.sensor_offset_y = 6.261034965515137e-06;
  c.sensor_offset_z = 3.7e-05;
  c.row_shift = 0;
  c.f_number = 2.081897119693584;
  c.mla_f_number = 2.0;
  c.focal_length = 0.013886307535794439;
  c.infinity_lambda = 15.409461826381099;
  // Three zooms (exit pupil moves with zoom, so the micro-image spacing does), two focus positions each.
  for (const auto& [zoom, pupil] : {std::pair{-1040, 0.046048875898122787}, {123, 0.060}, {1200, 0.085}})
    for (int focus : {-300, 814}) c.white_settings.push_back({zoom, focus, pupil});
  c.capture_setting = 3;  // zoom 123, focus 814, as in the real LFR
  c.full_well = 9000.0;
  c.read_noise = 1.2;
  c.exposure_duration = 0.03998677805066109;
  c.modulation_exposure_bias = 0.2447252869606018;
  return c;
}

CameraModel F01() {
  CameraModel c;
  c.name = "f01";
  c.model = "F01";
  c.white_model = "F01";
  c.firmware =
      "v1.0a119, vv1.0.2, Tue Jun 19 11:53:16 PDT 2012, cceebc3aa8e9dec7d959ea7daaa01d67ce7704af, mods=0, ofw=0";
  c.serial = "A203100001";
  c.sensor_serial = "0x0a1b2c3d";
  c.sensor_width = 3280;
  c.sensor_height = 3280;
  // Sensor, micro-lens array and colour (the responses are the inverse of the real white-balance gains).
  ApplyCameraFacts(decode::NominalCameraFacts("f01", "camera preset"), c);
  c.iso = 200;
  c.sensor_offset_x = -2.7138671874999998e-06;
  c.sensor_offset_y = 5.6601560115814212e-07;
  c.sensor_offset_z = 2.5000000000000001e-05;
  c.row_shift = 0;
  c.f_number = 1.9099999666213989;
  c.mla_f_number = 1.9;
  c.focal_length = 0.0064499998092651363;
  c.infinity_lambda = 7;
  for (const auto& [zoom, focus] : {std::pair{600, 430}, {981, 582}, {1400, 700}})
    c.white_settings.push_back({zoom, focus, 10000.0});
  c.capture_setting = 1;
  c.full_well = 7000.0;
  c.read_noise = 2.5;
  c.exposure_duration = 0.01433531753718853;
  c.modulation_exposure_bias = -1.1242823600769043;
  return c;
}

}  // namespace

double CameraModel::SpacingPixels(const LensSetting& setting) const {
  return lens_pitch / pixel_pitch * scale_x * (1.0 + sensor_offset_z / setting.exit_pupil);
}

double CameraModel::DiscRadius(const LensSetting& setting) const {
  // The micro-image is the image of the main-lens exit pupil: it fills the lens when the f-numbers match, less
  // when the main lens is stopped down; a small gap separates neighbouring discs.
  return 0.5 * SpacingPixels(setting) * std::min(1.0, mla_f_number / f_number) * 0.96;
}

std::array<double, 9> CameraModel::SceneToSensor() const {
  const std::array<double, 9>& m = ccm;
  const double det =
      m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) + m[2] * (m[3] * m[7] - m[4] * m[6]);
  if (!(std::abs(det) > 1e-9)) throw Error("camera '" + name + "': colour matrix is singular");
  const double inv = 1.0 / det;
  return {inv * (m[4] * m[8] - m[5] * m[7]), inv * (m[2] * m[7] - m[1] * m[8]), inv * (m[1] * m[5] - m[2] * m[4]),
          inv * (m[5] * m[6] - m[3] * m[8]), inv * (m[0] * m[8] - m[2] * m[6]), inv * (m[2] * m[3] - m[0] * m[5]),
          inv * (m[3] * m[7] - m[4] * m[6]), inv * (m[1] * m[6] - m[0] * m[7]), inv * (m[0] * m[4] - m[1] * m[3])};
}

CameraModel CameraPreset(const std::string& name) {
  if (name == "f01") return F01();
  if (name == "illum") {
    CameraModel c = IllumOptics();
    c.name = "illum";
    c.sensor_width = 7728;
    c.sensor_height = 5368;
    return c;
  }
  if (name == "mini-illum") {
    // Illum optics and micro-lenses on a 1024 x 768 crop: the same decoding problem, 50x fewer pixels.
    CameraModel c = IllumOptics();
    c.name = "mini-illum";
    c.sensor_width = 1024;
    c.sensor_height = 768;
    return c;
  }
  if (name == "mini-f01") {
    // F01 optics and micro-lenses on a 1024 x 1024 crop (a full F01 raw is 16 MB; this one 1.5 MB).
    CameraModel c = F01();
    c.name = "mini-f01";
    c.sensor_width = 1024;
    c.sensor_height = 1024;
    return c;
  }
  throw Error("camera '" + name + "': unknown (expected f01, illum, mini-illum or mini-f01)");
}

std::vector<std::string> CameraPresetNames() { return {"f01", "illum", "mini-illum", "mini-f01"}; }

double LensletLattice::RowSpacing() const { return spacing * kHalfSqrt3 * scale_y; }

HexLattice LensletLattice::Geometry() const {
  HexLattice geometry;
  geometry.spacing_x = spacing;
  geometry.spacing_y = RowSpacing();
  geometry.rotation = rotation;
  geometry.origin_x = origin_x;
  geometry.origin_y = origin_y;
  geometry.row_shift = row_shift;
  return geometry;
}

PixelPosition LensletLattice::Centre(int i, int j) const {
  double x = 0.0, y = 0.0;
  Geometry().Centre(i, j, x, y);
  return {static_cast<float>(x), static_cast<float>(y)};
}

void LensletLattice::LocalOffset(double x, double y, int i, int j, double& along, double& across) const {
  Geometry().LocalOffset(x, y, i, j, along, across);
}

void LensletLattice::Nearest(double x, double y, int& i, int& j) const { Geometry().Nearest(x, y, i, j); }

LensletLattice MakeLattice(const CameraModel& camera, const LensSetting& setting) {
  if (camera.sensor_width < 64 || camera.sensor_height < 64) throw Error("camera: sensor must be at least 64x64");
  LensletLattice lattice;
  lattice.spacing = camera.SpacingPixels(setting);
  lattice.scale_y = camera.scale_y;
  lattice.rotation = camera.rotation;
  // The lens nearest the optical axis sits at the sensor centre minus the sensor offset.
  lattice.origin_x = 0.5 * (camera.sensor_width - 1) - camera.sensor_offset_x / camera.pixel_pitch;
  lattice.origin_y = 0.5 * (camera.sensor_height - 1) - camera.sensor_offset_y / camera.pixel_pitch;
  lattice.row_shift = camera.row_shift;
  // Usable lenses: those whose whole micro-image is on the sensor.
  HexLattice geometry = lattice.Geometry();
  auto inside = [&](int i, int j) {
    double x = 0.0, y = 0.0;
    geometry.Centre(i, j, x, y);
    return geometry.MicroImageOnSensor(x, y, camera.sensor_width, camera.sensor_height);
  };
  const int reach = static_cast<int>(std::max(camera.sensor_width, camera.sensor_height) / lattice.spacing) + 4;
  const LensRange range = UsableLensRange(inside, reach, 0);
  // Re-index so that lens (0, 0) is the top-left usable lens.
  geometry.Reindex(range.i0, range.j0);
  lattice.row_shift = geometry.row_shift;
  lattice.origin_x = geometry.origin_x;
  lattice.origin_y = geometry.origin_y;
  lattice.columns = range.Columns();
  lattice.rows = range.Rows();
  return lattice;
}

DecodedGrid MakeDecodedGrid(const CameraModel& camera, const LensletLattice& lattice) {
  (void)camera;
  DecodedGrid grid;
  int n = static_cast<int>(std::ceil(lattice.spacing));
  if (n % 2 == 1) ++n;
  grid.views = n - 1;
  grid.view_step = lattice.spacing / n;
  grid.width = static_cast<int>(std::floor((lattice.columns - 1) / kHalfSqrt3)) + 1;
  grid.height = lattice.rows;
  return grid;
}

}  // namespace lfsp::simulate
