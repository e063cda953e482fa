#include "synthetic_lenslet.h"

#include <algorithm>
#include <cmath>

namespace lfsp::decode::testing {
namespace {

constexpr double kHalfSqrt3 = 0.86602540378443864676;

// A counter-based standard normal variate (splitmix64 + Box-Muller), so noise does not depend on threads.
double Gaussian(std::uint64_t seed, std::uint64_t index) {
  auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  const std::uint64_t a = mix(seed * 0x100000001b3ULL ^ (2 * index)),
                      b = mix(seed * 0x100000001b3ULL ^ (2 * index + 1));
  const double u1 = (static_cast<double>(a >> 11) + 0.5) / 9007199254740992.0;
  const double u2 = static_cast<double>(b >> 11) / 9007199254740992.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

SyntheticCamera IllumOptics() {
  SyntheticCamera c;
  c.spacing = 2e-5 / 1.4e-6 * (1.0 + 3.7e-5 / 0.06);
  c.scale_y = 1.0003466606140137;
  c.rotation = -0.0008558133849874139;
  c.format.packing = RawPacking::kBits10Illum;
  c.format.black = {64, 64, 64, 64};
  c.format.white = {1023, 1023, 1023, 1023};
  c.format.mosaic = BayerPattern::kGRBG;
  c.full_well = 9000.0;
  c.read_noise = 1.2;
  return c;
}

}  // namespace

void SyntheticCamera::Centre(int i, int j, double& x, double& y) const {
  const double a = (i + 0.5 * (((j % 2) + 2) % 2)) * spacing, b = j * spacing * kHalfSqrt3 * scale_y;
  const double c = std::cos(rotation), s = std::sin(rotation);
  x = axis_x + c * a - s * b;
  y = axis_y + s * a + c * b;
}

void SyntheticCamera::NearestCentre(double x, double y, double& cx, double& cy) const {
  const double c = std::cos(rotation), s = std::sin(rotation);
  const double dx = x - axis_x, dy = y - axis_y;
  const double b = (-s * dx + c * dy) / (spacing * kHalfSqrt3 * scale_y);
  double best = 1e300;
  const int j0 = static_cast<int>(std::floor(b));
  for (int j = j0; j <= j0 + 1; ++j) {
    const double a = (c * dx + s * dy) / spacing - 0.5 * (((j % 2) + 2) % 2);
    const int i = static_cast<int>(std::lround(a));
    double px = 0.0, py = 0.0;
    Centre(i, j, px, py);
    const double d = (px - x) * (px - x) + (py - y) * (py - y);
    if (d < best) {
      best = d;
      cx = px;
      cy = py;
    }
  }
}

GridGuess SyntheticCamera::Guess() const {
  GridGuess guess;
  guess.spacing = spacing;
  guess.scale_y = scale_y;
  guess.rotation = rotation;
  guess.axis_x = axis_x;
  guess.axis_y = axis_y;
  return guess;
}

SyntheticCamera IllumLikeCamera() {
  SyntheticCamera c = IllumOptics();
  c.width = 7728;
  c.height = 5368;
  c.axis_x = 0.5 * (c.width - 1) - 1.440673828125e-06 / 1.4e-6;
  c.axis_y = 0.5 * (c.height - 1) - 6.261034965515137e-06 / 1.4e-6;
  c.format.width = c.width;
  c.format.height = c.height;
  return c;
}

SyntheticCamera MiniCamera() {
  SyntheticCamera c = IllumOptics();
  c.width = 1024;
  c.height = 768;
  c.axis_x = 0.5 * (c.width - 1) - 1.440673828125e-06 / 1.4e-6;
  c.axis_y = 0.5 * (c.height - 1) - 6.261034965515137e-06 / 1.4e-6;
  c.format.width = c.width;
  c.format.height = c.height;
  return c;
}

SyntheticCamera F01LikeCamera() {
  SyntheticCamera c;
  c.width = 3280;
  c.height = 3280;
  c.spacing = 1.389859962463379e-05 / 1.3999999761581417e-06;
  c.scale_y = 1.0004994869232178;
  c.rotation = 0.0019290975760668516;
  c.axis_x = 0.5 * (c.width - 1) + 2.7138671874999998e-06 / 1.4e-6;
  c.axis_y = 0.5 * (c.height - 1) - 5.6601560115814212e-07 / 1.4e-6;
  c.disc_fraction = 0.475;
  c.format.width = c.width;
  c.format.height = c.height;
  c.format.packing = RawPacking::kBits12BigEndian;
  c.format.black = {168, 168, 168, 168};
  c.format.white = {4095, 4095, 4095, 4095};
  c.format.mosaic = BayerPattern::kBGGR;
  c.response_r = 1.1171875;
  c.response_b = 1.1171875 / 1.72265625;
  c.full_well = 7000.0;
  c.read_noise = 2.5;
  return c;
}

double Modulation(const SyntheticCamera& camera, double x, double y) {
  double cx = 0.0, cy = 0.0;
  camera.NearestCentre(x, y, cx, cy);
  const double disc = camera.disc_fraction * camera.spacing;
  const double r = std::hypot(x - cx, y - cy);
  // Soft edge about one pixel wide, and a cos^4-like falloff inside the disc.
  const double edge = std::clamp((disc - r) / 1.2 + 0.5, 0.0, 1.0);
  const double t = r / disc;
  const double falloff = std::max(0.0, 1.0 - 0.45 * t * t);
  const double inside = falloff * falloff;
  const double rx = (cx - 0.5 * camera.width) / camera.width, ry = (cy - 0.5 * camera.height) / camera.width;
  const double main_lens = 1.0 - 0.6 * (rx * rx + ry * ry);
  double cut = 1.0;
  if (camera.cats_eye > 0.0) {
    const double half_diagonal = 0.5 * std::hypot(camera.width, camera.height) / camera.width;
    const double rho = std::hypot(rx, ry) / half_diagonal;  // 0 at the centre, 1 in the corners
    if (rho > camera.cats_eye_start) {
      const double depth = (rho - camera.cats_eye_start) / (1.0 - camera.cats_eye_start);
      const double shift = camera.cats_eye * depth * depth * disc;
      const double ux = -rx / std::hypot(rx, ry), uy = -ry / std::hypot(rx, ry);
      const double r2 = std::hypot(x - (cx + shift * ux), y - (cy + shift * uy));
      cut = std::clamp((disc - r2) / 1.2 + 0.5, 0.0, 1.0);
    }
  }
  return edge * inside * main_lens * cut;
}

RawImage RenderWhiteRaw(const SyntheticCamera& camera, double exposure, std::uint64_t seed) {
  RawImage raw;
  raw.width = camera.width;
  raw.height = camera.height;
  raw.pixels.resize(raw.PixelCount());
  const double black = camera.format.black.gr, range = camera.format.white.gr - black;
  // Colour response per Bayer phase.
  const bool grbg = camera.format.mosaic == BayerPattern::kGRBG;
  auto response = [&](int x, int y) {
    const int phase = 2 * (y & 1) + (x & 1);
    const int red_phase = grbg ? 1 : 3, blue_phase = grbg ? 2 : 0;
    return phase == red_phase ? camera.response_r : phase == blue_phase ? camera.response_b : 1.0;
  };
#pragma omp parallel for schedule(dynamic, 16)
  for (int y = 0; y < raw.height; ++y) {
    for (int x = 0; x < raw.width; ++x) {
      const double signal = exposure * response(x, y) * Modulation(camera, x, y);
      double value = signal * range;
      if (camera.noise) {
        const std::uint64_t index = static_cast<std::uint64_t>(y) * raw.width + x;
        const double shot = std::sqrt(std::max(0.0, signal) * camera.full_well) / camera.full_well * range;
        value += shot * Gaussian(seed, index) + camera.read_noise * Gaussian(seed + 77, index);
      }
      raw.pixels[static_cast<std::size_t>(y) * raw.width + x] =
          static_cast<std::uint16_t>(std::clamp(std::lround(black + value), 0L, std::lround(black + range)));
    }
  }
  return raw;
}

}  // namespace lfsp::decode::testing
