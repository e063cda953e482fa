#include "lfsp/simulate/raw_capture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lfsp/core/error.h"
#include "ray_tracer.h"

namespace lfsp::simulate {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

// Counter-based random numbers: the value for (seed, index, stream) does not depend on evaluation order, so noise
// is identical whatever the thread count.
std::uint64_t SplitMix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double Uniform(std::uint64_t seed, std::uint64_t index, std::uint64_t stream) {
  const std::uint64_t h = SplitMix(SplitMix(seed ^ (stream * 0xd1342543de82ef95ULL)) + index);
  return (static_cast<double>(h >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

// Two independent standard normal values (Box-Muller).
std::pair<double, double> Normals(std::uint64_t seed, std::uint64_t index) {
  const double u1 = Uniform(seed, index, 1);
  const double u2 = Uniform(seed, index, 2);
  const double r = std::sqrt(-2.0 * std::log(u1));
  return {r * std::cos(2.0 * 3.14159265358979323846 * u2), r * std::sin(2.0 * 3.14159265358979323846 * u2)};
}

// Colour channel (0 r, 1 g, 2 b) of sensor pixel (x, y) for a 2x2 tile such as "grbg".
std::array<int, 4> BayerTile(const std::string& pattern) {
  if (pattern.size() != 4) throw Error("camera: Bayer pattern '" + pattern + "' must have 4 letters");
  std::array<int, 4> tile{};
  for (int k = 0; k < 4; ++k) {
    const char c = pattern[static_cast<std::size_t>(k)];
    if (c == 'r')
      tile[static_cast<std::size_t>(k)] = 0;
    else if (c == 'g')
      tile[static_cast<std::size_t>(k)] = 1;
    else if (c == 'b')
      tile[static_cast<std::size_t>(k)] = 2;
    else
      throw Error("camera: Bayer pattern '" + pattern + "' may only contain r, g, b");
  }
  return tile;
}

// The lattice with its rotation precomputed, for the per-pixel loops: nearest lens and the offset from its centre
// in one step (same results as LensletLattice::Nearest + LocalOffset).
struct FastLattice {
  explicit FastLattice(const LensletLattice& l)
      : lattice(l), c(std::cos(l.rotation)), s(std::sin(l.rotation)), row(l.RowSpacing()) {}
  void Locate(double x, double y, int& i, int& j, double& along, double& across) const {
    const double dx = x - lattice.origin_x, dy = y - lattice.origin_y;
    const double qa = c * dx + s * dy;
    const double qb = -s * dx + c * dy;
    const int j0 = static_cast<int>(std::floor(qb / row));
    double best = std::numeric_limits<double>::max();
    for (int jj = j0; jj <= j0 + 1; ++jj) {
      const double shift = 0.5 * lattice.Shift(jj);
      const int ii = static_cast<int>(std::lround(qa / lattice.spacing - shift));
      const double ea = qa - (ii + shift) * lattice.spacing;
      const double eb = qb - jj * row;
      const double dist = ea * ea + eb * eb;
      if (dist < best) {
        best = dist;
        i = ii;
        j = jj;
        along = ea;
        across = eb;
      }
    }
  }
  const LensletLattice& lattice;
  double c, s, row;
};

double MicroLensProfile(double r, double disc_radius) {
  // Smooth radial falloff inside the disc (paraboloid in the core, as in real white images the micro-image is
  // brightest at its centre) with a soft edge about 0.7 px wide.
  const double core = 1.0 - 0.45 * (r / disc_radius) * (r / disc_radius);
  const double edge = (r - disc_radius) / 0.7;
  if (edge < -12.0) return core;  // tanh is -1 to double precision: skip it
  return std::max(0.0, core) * 0.5 * (1.0 - std::tanh(edge));
}

double MainLensFalloff(const CameraModel& camera, double x, double y) {
  const double cx = 0.5 * (camera.sensor_width - 1), cy = 0.5 * (camera.sensor_height - 1);
  const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / (cx * cx + cy * cy);
  return 1.0 - 0.15 * r2;
}

struct SensorSetup {
  LensSetting setting;
  LensletLattice lattice;
  DecodedGrid grid;
  double disc_radius = 0;
  std::array<int, 4> tile{};
  std::array<double, 3> response{};
  std::array<double, 9> scene_to_sensor{};  // CameraModel::SceneToSensor
};

SensorSetup Setup(const CameraModel& camera, int setting_index) {
  if (setting_index < 0 || setting_index >= static_cast<int>(camera.white_settings.size()))
    throw Error("camera '" + camera.name + "': lens setting " + std::to_string(setting_index) + " does not exist");
  SensorSetup s;
  s.setting = camera.white_settings[static_cast<std::size_t>(setting_index)];
  s.lattice = MakeLattice(camera, s.setting);
  s.grid = MakeDecodedGrid(camera, s.lattice);
  s.disc_radius = camera.DiscRadius(s.setting);
  s.tile = BayerTile(camera.bayer);
  s.response = {camera.response_r, 1.0, camera.response_b};
  s.scene_to_sensor = camera.SceneToSensor();
  return s;
}

// Converts a signal (fraction of white - black) to a stored value with shot and read noise.
std::uint16_t Digitise(const CameraModel& camera, double signal, double full_well, bool noise, std::uint64_t seed,
                       std::uint64_t index) {
  double dn = camera.black + signal * (camera.white - camera.black);
  if (noise) {
    const auto [n1, n2] = Normals(seed, index);
    const double electrons = std::max(0.0, signal) * full_well;
    dn += n1 * std::sqrt(electrons) / full_well * (camera.white - camera.black) + n2 * camera.read_noise;
  }
  const double max_code = static_cast<double>((1 << camera.bits) - 1);
  return static_cast<std::uint16_t>(std::clamp(std::nearbyint(dn), 0.0, std::min(max_code, double(camera.white))));
}

void AddHotPixels(const CameraModel& camera, int count, std::uint64_t seed, RawCapture& raw) {
  for (int k = 0; k < count; ++k) {
    const int x =
        std::min(raw.width - 1, static_cast<int>(Uniform(seed, static_cast<std::uint64_t>(k), 7) * raw.width));
    const int y =
        std::min(raw.height - 1, static_cast<int>(Uniform(seed, static_cast<std::uint64_t>(k), 8) * raw.height));
    raw.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(raw.width) + static_cast<std::size_t>(x)] =
        static_cast<std::uint16_t>(camera.white);
    raw.hot_pixels.push_back({x, y});
  }
}

RawCapture EmptyCapture(const CameraModel& camera, const SensorSetup& s) {
  RawCapture raw;
  raw.width = camera.sensor_width;
  raw.height = camera.sensor_height;
  raw.pixels.assign(static_cast<std::size_t>(raw.width) * static_cast<std::size_t>(raw.height), 0);
  raw.setting = s.setting;
  raw.lattice = s.lattice;
  raw.grid = s.grid;
  return raw;
}

// n x n points spread evenly over one micro-lens's aperture, as offsets from the lens centre in decoded pixels
// (lenses are 1/cos 30 deg apart along a row, rows 1 apart). The points cover the brick-shaped cell (one lens pitch
// by one row, a fundamental domain of the lattice) one per cell of an n x n grid, and no two share a column or a
// row of the finer n^2 x n^2 grid (Chiu, Shirley and Wang's canonical multi-jittered layout, without the jitter): a
// straight edge along either axis then reads in steps of 1/n^2 of a lens, not 1/n. Folding each point onto the
// lattice point nearest to it moves it into the lens's own hexagonal (Voronoi) cell without changing the spread.
std::vector<std::array<double, 2>> LensApertureOffsets(int n) {
  const double pitch = 1.0 / kHalfSqrt3;
  const std::array<std::array<double, 2>, 7> lattice{
      {{0, 0}, {pitch, 0}, {-pitch, 0}, {0.5 * pitch, 1}, {-0.5 * pitch, 1}, {0.5 * pitch, -1}, {-0.5 * pitch, -1}}};
  std::vector<std::array<double, 2>> offsets;
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) {
      const double x = ((a + (b + 0.5) / n) / n - 0.5) * pitch, y = (b + (a + 0.5) / n) / n - 0.5;
      std::array<double, 2> nearest = lattice[0];
      for (const auto& l : lattice)
        if (std::hypot(x - l[0], y - l[1]) < std::hypot(x - nearest[0], y - nearest[1])) nearest = l;
      offsets.push_back({x - nearest[0], y - nearest[1]});
    }
  return offsets;
}

}  // namespace

double Modulation(const CameraModel& camera, const LensletLattice& lattice, double disc_radius, double x, double y,
                  int i, int j) {
  double along = 0, across = 0;
  lattice.LocalOffset(x, y, i, j, along, across);
  return MicroLensProfile(std::hypot(along, across), disc_radius) * MainLensFalloff(camera, x, y);
}

void CheckCaptureOptions(const CaptureOptions& options) {
  if (options.supersampling < 1 || options.supersampling > 8) throw Error("capture: supersampling must be 1..8");
  if (options.lens_samples < 0 || options.lens_samples > 8) throw Error("capture: lens samples must be 0..8");
  if (!(options.exposure > 0.0 && options.exposure <= 4.0)) throw Error("capture: exposure must be in (0, 4]");
  if (options.hot_pixels < 0) throw Error("capture: hot pixel count must be >= 0");
  if (!std::isfinite(options.disparity_scale)) throw Error("capture: disparity scale must be finite");
}

RawCapture RenderRawCapture(const Scene& scene, const CameraModel& camera, const CaptureOptions& options) {
  CheckCaptureOptions(options);
  const SensorSetup s = Setup(camera, camera.capture_setting);
  RawCapture raw = EmptyCapture(camera, s);
  raw.exposure = options.exposure;
  const float max_offset = static_cast<float>(s.disc_radius / s.grid.view_step + 2.0);
  const RayTracer tracer(scene, s.grid.width, s.grid.height, options.disparity_scale, max_offset, Transfer::kLinear);
  const int k = options.supersampling;
  const std::vector<std::array<double, 2>> aperture =
      LensApertureOffsets(options.lens_samples == 0 ? kDefaultLensSamples : options.lens_samples);
  const double inv_rays = 1.0 / static_cast<double>(k * k * aperture.size());
  const double inv_step = 1.0 / s.grid.view_step;
  const double decoded_per_lens = 1.0 / kHalfSqrt3;
  const double cut = s.disc_radius + 3.0;  // beyond this the profile is < 1e-3 of its peak: skip tracing
  const FastLattice fast(s.lattice);
#pragma omp parallel for schedule(dynamic, 8)
  for (int y = 0; y < raw.height; ++y) {
    std::uint16_t* row = raw.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(raw.width);
    for (int x = 0; x < raw.width; ++x) {
      const int channel = s.tile[static_cast<std::size_t>((y & 1) * 2 + (x & 1))];
      // This pixel's colour filter sees the scene through the inverse of the metadata's colour matrix.
      const double* to_sensor = &s.scene_to_sensor[3 * static_cast<std::size_t>(channel)];
      double sum = 0.0;
      for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a) {
          const double sx = x + (a + 0.5) / k - 0.5, sy = y + (b + 0.5) / k - 0.5;
          int i = 0, j = 0;
          double along = 0, across = 0;
          fast.Locate(sx, sy, i, j, along, across);
          const double r = std::sqrt(along * along + across * across);
          if (r > cut) continue;
          const double m = MicroLensProfile(r, s.disc_radius) * MainLensFalloff(camera, sx, sy);
          // The lens gives the spatial sample (decoded grid), the offset within its micro-image the view.
          const double lens_x = (i + 0.5 * s.lattice.Shift(j)) * decoded_per_lens, lens_y = j;
          const auto vs = static_cast<float>(along * inv_step), vt = static_cast<float>(across * inv_step);
          for (const auto& offset : aperture) {
            const RayHit hit =
                tracer.Trace(static_cast<float>(lens_x + offset[0]), static_cast<float>(lens_y + offset[1]), vs, vt);
            const Rgb c = tracer.Shade(hit, vs, vt);
            sum += m * (to_sensor[0] * c[0] + to_sensor[1] * c[1] + to_sensor[2] * c[2]);
          }
        }
      const double signal = options.exposure * s.response[static_cast<std::size_t>(channel)] * sum * inv_rays;
      row[x] = Digitise(
          camera, signal, camera.full_well, options.noise, options.seed,
          static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(raw.width) + static_cast<std::uint64_t>(x));
    }
  }
  AddHotPixels(camera, options.hot_pixels, options.seed, raw);
  return raw;
}

RawCapture RenderWhiteImage(const CameraModel& camera, int setting_index, std::uint64_t seed) {
  const SensorSetup s = Setup(camera, setting_index);
  RawCapture raw = EmptyCapture(camera, s);
  raw.exposure = 0.8;
  // White images are averages of many exposures in the camera's calibration: less noise than a capture.
  const double full_well = camera.full_well * 16.0;
  const FastLattice fast(s.lattice);
  const std::uint64_t white_seed = SplitMix(seed ^ (0x5748495445ULL + static_cast<std::uint64_t>(setting_index)));
#pragma omp parallel for schedule(static)
  for (int y = 0; y < raw.height; ++y) {
    std::uint16_t* row = raw.pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(raw.width);
    for (int x = 0; x < raw.width; ++x) {
      const int channel = s.tile[static_cast<std::size_t>((y & 1) * 2 + (x & 1))];
      int i = 0, j = 0;
      double along = 0, across = 0;
      fast.Locate(x, y, i, j, along, across);
      const double m =
          MicroLensProfile(std::sqrt(along * along + across * across), s.disc_radius) * MainLensFalloff(camera, x, y);
      const double signal = raw.exposure * s.response[static_cast<std::size_t>(channel)] * m;
      row[x] = Digitise(
          camera, signal, full_well, true, white_seed,
          static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(raw.width) + static_cast<std::uint64_t>(x));
    }
  }
  return raw;
}

RenderedLightField RenderDecodedGroundTruth(const Scene& scene, const CameraModel& camera,
                                            const CaptureOptions& options, int supersampling) {
  const SensorSetup s = Setup(camera, camera.capture_setting);
  RenderOptions render;
  render.nu = render.nv = s.grid.views;
  render.width = s.grid.width;
  render.height = s.grid.height;
  render.supersampling = supersampling;
  render.disparity_scale = options.disparity_scale;
  render.transfer = Transfer::kLinear;
  render.per_view_disparity = false;
  RenderedLightField gt = RenderLightField(scene, render);
  // Weight of each ray = the modulation its sensor pixel receives: micro-lens profile at the view's offset times
  // the main-lens falloff at the lens. Views outside the disc get weight ~0, as a decoder's weight channel would.
  // Quantised to 1/4096 (far below any use of a weight) so that the ground-truth files compress well.
  LightField& lf = gt.light_field;
  lf.EnableWeights(0.0f);
  const int views = s.grid.views;
  const int uc = (views - 1) / 2;
#pragma omp parallel for collapse(2) schedule(static)
  for (int v = 0; v < views; ++v)
    for (int u = 0; u < views; ++u) {
      const double r = std::hypot(u - uc, v - uc) * s.grid.view_step;
      const double micro = MicroLensProfile(r, s.disc_radius);
      float* w = lf.weights().ViewData({u, v});
      const double c = std::cos(s.lattice.rotation), sn = std::sin(s.lattice.rotation);
      for (int y = 0; y < s.grid.height; ++y)
        for (int x = 0; x < s.grid.width; ++x) {
          const double a = x * kHalfSqrt3 * s.lattice.spacing, b = y * s.lattice.RowSpacing();
          const double sx = s.lattice.origin_x + c * a - sn * b, sy = s.lattice.origin_y + sn * a + c * b;
          w[static_cast<std::size_t>(y) * static_cast<std::size_t>(s.grid.width) + static_cast<std::size_t>(x)] =
              static_cast<float>(std::round(micro * MainLensFalloff(camera, sx, sy) * 4096.0) / 4096.0);
        }
    }
  lf.metadata["simulate"]["camera"] = camera.name;
  lf.metadata["simulate"]["decoded_grid"] = {
      {"views", views}, {"view_step_pixels", s.grid.view_step}, {"width", s.grid.width}, {"height", s.grid.height}};
  return gt;
}

}  // namespace lfsp::simulate
