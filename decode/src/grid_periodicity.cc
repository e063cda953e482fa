// Lenslet grid estimation from the lattice's periodicity: works on ordinary captures (scene content, dark and
// saturated regions, JPEG blocking), where centroids of single micro-images are pulled by the scene.
//
// The micro-images repeat on a hexagonal lattice, so the image's local contrast (its dark side: the gaps between the
// micro-images and the rims of their discs, which neither the scene nor the main lens's vignetting moves) has sharp
// spectral peaks at the six first-ring reciprocal vectors; the scene does not. Three steps:
//   1. the power spectrum of a central crop gives the reciprocal vectors coarsely (the three peaks 60 degrees apart
//      with the most power: JPEG's 8-pixel blocking has no partners at 60 degrees);
//   2. each block of about 12 x 12 lenses is demodulated at those vectors; the phase of each block says where the
//      lattice sits in it, so fitting a plane to the phases over the sensor refines the vectors and gives the
//      position of the lattice, averaged over every block (content and noise average out; every block with a clear
//      lattice signal counts the same, dark and flat ones not at all);
//   3. the vectors and position become the hexagonal lattice model, indexed as the white-image fit indexes it.

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "lattice.h"
#include "lfsp/core/error.h"
#include "lfsp/decode/lenslet_grid.h"

namespace lfsp::decode {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kHalfSqrt3 = 0.86602540378443864676;
constexpr double kMinPeakContrast = 100.0;  // whitened power each first-ring peak of a lattice must reach
const cv::Matx<float, 1, 5> kBinomial5(0.0625f, 0.25f, 0.375f, 0.25f, 0.0625f);  // [1 4 6 4 1] / 16

struct Frequency {
  double x = 0.0;  // cycles per pixel
  double y = 0.0;
  double Dot(double px, double py) const { return x * px + y * py; }
  double Norm() const { return std::hypot(x, y); }
  Frequency Rotated(double angle) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * x - s * y, s * x + c * y};
  }
};

double Wrap(double phase) { return std::remainder(phase, kTwoPi); }

// The image's local contrast, (I - local mean) / local mean over about two lens pitches: the lattice is then equally
// strong in bright and dim regions.
//
// Only its dark side is kept (values above the local mean become 0): the gaps between the micro-images and the rims of
// their discs, which the micro-lenses' edges fix. The bright inside of a disc carries what the lens sees, and away from
// the optical axis the main lens's vignetting tilts it towards the axis (the real F01 frames' mean micro-image near the
// sensor's edges is a few percent brighter on its inner side, its rim still centred): a lattice phase from the whole
// disc then puts every lens a little towards the middle, more the further out, as a lattice 1e-4 too small (0.16 px
// at the edges). From the dark side alone the frames' spacing matches the camera's centre table.
//
// The Bayer pattern goes first: a coloured scene leaves a checkerboard of bright and dark pixels inside the discs,
// which the cut at the mean would turn from a Nyquist-frequency pattern (that neither the spectrum nor the block
// demodulation sees) into dark specks that move the phase (IMG_3: 0.1 px). Its colour also follows each disc's
// vignetting, which puts sidebands at the Nyquist frequency minus the lattice's first ring (0.38-0.40 cycles per px),
// and the cut at the mean mixes those into the lattice's own frequencies. [1 2 1] / 4 along both axes (zero at the
// Nyquist frequency) passed 9.5-13 % of them, and the real F01 frames' spacing then depended on their colour (the
// restored mosaic's against the plain JPEG decode's). [1 4 6 4 1] / 16, the same filter twice, passes 0.9-1.6 % of
// them and 76 % of the lattice's first ring (BENCHMARKS.md, thirty-ninth session).
cv::Mat LocalContrast(const cv::Mat& grey, double spacing) {
  cv::Mat smooth;
  cv::sepFilter2D(grey, smooth, CV_32F, kBinomial5, kBinomial5, cv::Point(-1, -1), 0.0, cv::BORDER_REFLECT);
  const int box = 2 * static_cast<int>(std::lround(spacing)) + 1;
  cv::Mat local;
  cv::blur(smooth, local, cv::Size(box, box), cv::Point(-1, -1), cv::BORDER_REFLECT);
  const float floor = static_cast<float>(std::max(1e-6, 0.05 * cv::mean(local)[0]));
  cv::Mat contrast(grey.size(), CV_32F);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < grey.rows; ++y) {
    const float* s = smooth.ptr<float>(y);
    const float* m = local.ptr<float>(y);
    float* out = contrast.ptr<float>(y);
    for (int x = 0; x < grey.cols; ++x) out[x] = std::clamp((s[x] - m[x]) / std::max(m[x], floor), -2.0f, 0.0f);
  }
  return contrast;
}

// Power spectrum of a central square crop (Hann-windowed), whitened by its median power at each radius so that the
// lattice peaks stand out from the scene's falloff (a median, so that the peaks themselves do not raise it). Index
// (v, u) holds frequency ((u - side/2) / side, (v - side/2) / side).
cv::Mat WhitenedSpectrum(const cv::Mat& contrast, int side) {
  const cv::Rect crop((contrast.cols - side) / 2, (contrast.rows - side) / 2, side, side);
  cv::Mat windowed;
  cv::createHanningWindow(windowed, cv::Size(side, side), CV_32F);
  windowed = windowed.mul(contrast(crop));
  cv::Mat spectrum;
  cv::dft(windowed, spectrum, cv::DFT_COMPLEX_OUTPUT);
  cv::Mat power(side, side, CV_64F);
  std::vector<std::vector<double>> rings(static_cast<std::size_t>(side));
  auto ring_of = [side](int u, int v) {
    return static_cast<std::size_t>(std::lround(std::hypot(u - side / 2, v - side / 2)));
  };
  for (int v = 0; v < side; ++v)
    for (int u = 0; u < side; ++u) {
      const cv::Vec2f c = spectrum.at<cv::Vec2f>(v, u);
      // Shift zero frequency to the middle.
      const int su = (u + side / 2) % side, sv = (v + side / 2) % side;
      const double p = static_cast<double>(c[0]) * c[0] + static_cast<double>(c[1]) * c[1];
      power.at<double>(sv, su) = p;
      if (ring_of(su, sv) < rings.size()) rings[ring_of(su, sv)].push_back(p);
    }
  std::vector<double> median(rings.size(), 0.0);
  for (std::size_t r = 0; r < rings.size(); ++r) {
    std::vector<double>& ring = rings[r];
    if (ring.empty()) continue;
    std::nth_element(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(ring.size() / 2), ring.end());
    median[r] = ring[ring.size() / 2];
  }
  for (int v = 0; v < side; ++v)
    for (int u = 0; u < side; ++u) {
      const std::size_t r = ring_of(u, v);
      const double floor = r < median.size() ? median[r] : 0.0;
      power.at<double>(v, u) = floor > 0.0 ? power.at<double>(v, u) / floor : 0.0;
    }
  return power;
}

// Whitened power near frequency f (the largest of the 3 x 3 bins around it), 0 off the spectrum.
double PowerNear(const cv::Mat& power, const Frequency& f) {
  const int side = power.cols;
  const int u = static_cast<int>(std::lround(f.x * side)) + side / 2;
  const int v = static_cast<int>(std::lround(f.y * side)) + side / 2;
  double best = 0.0;
  for (int dv = -1; dv <= 1; ++dv)
    for (int du = -1; du <= 1; ++du)
      if (u + du >= 0 && u + du < side && v + dv >= 0 && v + dv < side)
        best = std::max(best, power.at<double>(v + dv, u + du));
  return best;
}

// A lattice's strength at first-ring vector k: the power of the three first-ring peaks k, R60 k, R120 k.
double HexScore(const cv::Mat& power, const Frequency& k) {
  return PowerNear(power, k) + PowerNear(power, k.Rotated(std::numbers::pi / 3)) +
         PowerNear(power, k.Rotated(2 * std::numbers::pi / 3));
}

// Sub-bin peak position by a parabola through the log power of the neighbouring bins, starting near f.
Frequency RefinePeak(const cv::Mat& power, const Frequency& f) {
  const int side = power.cols;
  int u = static_cast<int>(std::lround(f.x * side)) + side / 2;
  int v = static_cast<int>(std::lround(f.y * side)) + side / 2;
  double best = -1.0;
  int bu = u, bv = v;
  for (int dv = -1; dv <= 1; ++dv)
    for (int du = -1; du <= 1; ++du)
      if (u + du >= 1 && u + du < side - 1 && v + dv >= 1 && v + dv < side - 1 &&
          power.at<double>(v + dv, u + du) > best) {
        best = power.at<double>(v + dv, u + du);
        bu = u + du;
        bv = v + dv;
      }
  if (bu < 1 || bv < 1 || bu >= side - 1 || bv >= side - 1) return f;
  auto offset = [](double left, double centre, double right) {
    const double l = std::log(left + 1e-30), c = std::log(centre + 1e-30), r = std::log(right + 1e-30);
    const double denominator = l - 2.0 * c + r;
    return denominator < 0.0 ? std::clamp(0.5 * (l - r) / denominator, -0.5, 0.5) : 0.0;
  };
  const double du = offset(power.at<double>(bv, bu - 1), best, power.at<double>(bv, bu + 1));
  const double dv = offset(power.at<double>(bv - 1, bu), best, power.at<double>(bv + 1, bu));
  return {(bu - side / 2 + du) / side, (bv - side / 2 + dv) / side};
}

// Step 1: two first-ring reciprocal vectors 60 degrees apart, for a lens spacing in [min_spacing, max_spacing].
std::array<Frequency, 2> CoarseReciprocal(const cv::Mat& contrast, double min_spacing, double max_spacing) {
  int side = 1;
  // 1024 bins resolve the peaks to ~1e-4 cycles per pixel, far finer than the phase-plane fit needs to take over.
  while (side * 2 <= std::min({contrast.cols, contrast.rows, 1024})) side *= 2;
  if (side < std::min(contrast.cols, contrast.rows) && side < 256)
    side = std::min(contrast.cols, contrast.rows) & ~1;  // small images: use all of them
  const cv::Mat power = WhitenedSpectrum(contrast, side);
  // First-ring frequency = 1 / row spacing = 2 / (sqrt(3) spacing).
  const double f_min = 1.0 / (kHalfSqrt3 * max_spacing), f_max = 1.0 / (kHalfSqrt3 * min_spacing);
  double best = -1.0;
  Frequency best_k;
  const int reach = static_cast<int>(std::ceil(f_max * side));
  for (int v = 0; v <= std::min(reach, side / 2 - 1); ++v)
    for (int u = -std::min(reach, side / 2 - 1); u <= std::min(reach, side / 2 - 1); ++u) {
      const Frequency k{static_cast<double>(u) / side, static_cast<double>(v) / side};
      const double f = k.Norm();
      if (f < f_min || f > f_max || (v == 0 && u <= 0)) continue;
      const double score = HexScore(power, k);
      if (score > best) {
        best = score;
        best_k = k;
      }
    }
  if (!(best > 0.0)) throw Error("lenslet grid: no lattice frequency found in the image");
  // A harmonic ring of a coarser lattice also looks hexagonal: prefer the coarser lattice when it is clearly there.
  for (bool coarser = true; coarser;) {
    coarser = false;
    const std::array<Frequency, 2> subharmonics = {Frequency{best_k.x / 2, best_k.y / 2},
                                                   Frequency{best_k.Rotated(std::numbers::pi / 6).x / std::sqrt(3.0),
                                                             best_k.Rotated(std::numbers::pi / 6).y / std::sqrt(3.0)}};
    for (const Frequency& candidate : subharmonics) {
      if (candidate.Norm() < f_min) continue;
      if (HexScore(power, candidate) >= 0.2 * best) {
        best_k = candidate;
        best = HexScore(power, candidate);
        coarser = true;
        break;
      }
    }
  }
  // A lenslet image's three peaks stand 10^4..10^6 times above the spectrum's median at their radius (measured on real
  // and simulated F01 and Illum images); the best hexagon in a photograph or in noise reaches about 8.
  const double weakest = std::min({PowerNear(power, best_k), PowerNear(power, best_k.Rotated(std::numbers::pi / 3)),
                                   PowerNear(power, best_k.Rotated(2 * std::numbers::pi / 3))});
  if (weakest < kMinPeakContrast)
    throw Error("lenslet grid: the image shows no micro-lens lattice (its strongest hexagonal spectral peaks are " +
                std::to_string(static_cast<int>(weakest)) + " x the background; a lenslet image's exceed 10000)");
  const Frequency k1 = RefinePeak(power, best_k);
  const Frequency k2 = RefinePeak(power, k1.Rotated(std::numbers::pi / 3));
  return {k1, k2};
}

// One block's demodulated lattice signal at the three first-ring vectors.
struct BlockPhases {
  double cx = 0.0;  // block centre, px
  double cy = 0.0;
  int column = 0;  // position in the block grid
  int row = 0;
  std::array<Complex, 3> z{};
};

// Step 2a: z_m = sum over the block of hann(p) contrast(p) exp(-2 pi i k_m . (p - centre)).
std::vector<BlockPhases> DemodulateBlocks(const cv::Mat& contrast, const std::array<Frequency, 3>& k, int block,
                                          int step, int& columns, int& rows) {
  columns = std::max(1, (contrast.cols - block) / step + 1);
  rows = std::max(1, (contrast.rows - block) / step + 1);
  std::vector<double> window(static_cast<std::size_t>(block));
  for (int t = 0; t < block; ++t)
    window[static_cast<std::size_t>(t)] = 0.5 - 0.5 * std::cos(kTwoPi * (t + 0.5) / block);
  std::vector<BlockPhases> blocks(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows));
#pragma omp parallel for schedule(dynamic, 1)
  for (int by = 0; by < rows; ++by) {
    std::vector<Complex> along(static_cast<std::size_t>(block) * 3);
    for (int bx = 0; bx < columns; ++bx) {
      BlockPhases& b = blocks[static_cast<std::size_t>(by) * columns + static_cast<std::size_t>(bx)];
      const int x0 = bx * step, y0 = by * step;
      b.column = bx;
      b.row = by;
      b.cx = x0 + 0.5 * (block - 1);
      b.cy = y0 + 0.5 * (block - 1);
      for (int m = 0; m < 3; ++m)
        for (int t = 0; t < block; ++t)
          along[static_cast<std::size_t>(m * block + t)] =
              window[static_cast<std::size_t>(t)] * std::polar(1.0, -kTwoPi * k[m].x * (x0 + t - b.cx));
      std::array<Complex, 3> sum{};
      for (int t = 0; t < block && y0 + t < contrast.rows; ++t) {
        const float* row = contrast.ptr<float>(y0 + t);
        for (int m = 0; m < 3; ++m) {
          Complex line = 0.0;
          const Complex* e = &along[static_cast<std::size_t>(m * block)];
          for (int s = 0; s < block && x0 + s < contrast.cols; ++s) line += static_cast<double>(row[x0 + s]) * e[s];
          sum[m] += line * window[static_cast<std::size_t>(t)] * std::polar(1.0, -kTwoPi * k[m].y * (y0 + t - b.cy));
        }
      }
      b.z = sum;
    }
  }
  return blocks;
}

// The lattice phase of one reciprocal vector over the sensor: phase(p) = 2 pi (k + dk) . p + offset.
struct PhasePlane {
  Frequency k;
  double offset = 0.0;  // rad, at p = 0
  double rms = 0.0;     // rad, weighted RMS of the inlier blocks about the plane
  int inliers = 0;
};

// Step 2b: refine k from one reciprocal vector's block phases. First the phase step between neighbouring blocks
// (a weighted circular mean, robust to the wraps), then a weighted least-squares plane through the unwrapped phases
// with outlier blocks dropped.
PhasePlane FitPhasePlane(const std::vector<BlockPhases>& blocks, int m, Frequency k, int columns, int rows,
                         double step) {
  auto at = [&](int bx, int by) -> const BlockPhases& {
    return blocks[static_cast<std::size_t>(by) * columns + static_cast<std::size_t>(bx)];
  };
  // Neighbour phase steps: z(b') conj z(b) exp(-2 pi i k . (c' - c)) has the phase 2 pi dk . (c' - c).
  Complex horizontal = 0.0, vertical = 0.0;
  for (int by = 0; by < rows; ++by)
    for (int bx = 0; bx < columns; ++bx) {
      const BlockPhases& b = at(bx, by);
      if (bx + 1 < columns)
        horizontal += at(bx + 1, by).z[m] * std::conj(b.z[m]) * std::polar(1.0, -kTwoPi * k.x * step);
      if (by + 1 < rows) vertical += at(bx, by + 1).z[m] * std::conj(b.z[m]) * std::polar(1.0, -kTwoPi * k.y * step);
    }
  if (columns > 1) k.x += std::arg(horizontal) / (kTwoPi * step);
  if (rows > 1) k.y += std::arg(vertical) / (kTwoPi * step);

  PhasePlane plane;
  std::vector<double> weight(blocks.size());
  // Every block with a clear lattice signal counts the same: weighting by signal strength would let the few most
  // contrasted blocks (bright texture) set the spacing (measured on the real F01 frames: p95 0.83 -> 0.78 px).
  std::vector<double> strength(blocks.size());
  for (std::size_t n = 0; n < blocks.size(); ++n) strength[n] = std::abs(blocks[n].z[m]);
  std::vector<double> sorted = strength;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double clear = 0.25 * sorted[sorted.size() / 2];
  for (std::size_t n = 0; n < blocks.size(); ++n) weight[n] = strength[n] >= clear && strength[n] > 0.0 ? 1.0 : 0.0;
  double centre_x = 0.0, centre_y = 0.0, total = 0.0;
  for (std::size_t n = 0; n < blocks.size(); ++n) {
    centre_x += weight[n] * blocks[n].cx;
    centre_y += weight[n] * blocks[n].cy;
    total += weight[n];
  }
  if (!(total > 0.0)) throw Error("lenslet grid: the image shows no lattice");
  centre_x /= total;
  centre_y /= total;
  std::vector<bool> inlier(blocks.size(), true);
  double dkx = 0.0, dky = 0.0, offset = 0.0;  // phase about the weighted centre: offset + 2 pi dk . (c - centre)
  for (int iteration = 0; iteration < 4; ++iteration) {
    // Phase of each block after removing the current model; its circular mean starts the unwrapping.
    std::vector<double> residual(blocks.size());
    Complex mean = 0.0;
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      const double model = kTwoPi * ((k.x + dkx) * (blocks[n].cx - centre_x) + (k.y + dky) * (blocks[n].cy - centre_y) +
                                     k.x * centre_x + k.y * centre_y);
      residual[n] = Wrap(std::arg(blocks[n].z[m]) - model);
      if (inlier[n]) mean += weight[n] * std::polar(1.0, residual[n]);
    }
    const double level = std::arg(mean);
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      if (!inlier[n]) continue;
      const Eigen::Vector3d row(1.0, kTwoPi * (blocks[n].cx - centre_x), kTwoPi * (blocks[n].cy - centre_y));
      normal += weight[n] * row * row.transpose();
      rhs += weight[n] * row * (level + Wrap(residual[n] - level));
    }
    Eigen::Vector3d solution = Eigen::Vector3d::Zero();
    if (columns * rows >= 3 && std::abs(normal.determinant()) > 1e-12 * std::pow(normal.trace(), 3))
      solution = normal.ldlt().solve(rhs);
    else
      solution(0) = level;
    offset = solution(0);
    dkx += solution(1);
    dky += solution(2);
    // Drop blocks far from the plane (4 robust sigmas, never closer than 0.15 rad).
    std::vector<std::pair<double, double>> deviations;
    double sum_squares = 0.0, sum_weights = 0.0;
    std::vector<double> deviation(blocks.size());
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      const double model =
          offset + kTwoPi * (solution(1) * (blocks[n].cx - centre_x) + solution(2) * (blocks[n].cy - centre_y));
      deviation[n] = std::abs(Wrap(level + Wrap(residual[n] - level) - model));
      if (weight[n] > 0.0) deviations.emplace_back(deviation[n], weight[n]);
    }
    std::sort(deviations.begin(), deviations.end());
    double half = 0.0, accumulated = 0.0, weighted_median = 0.0;
    for (const auto& [value, w] : deviations) half += w;
    for (const auto& [value, w] : deviations) {
      accumulated += w;
      if (accumulated >= 0.5 * half) {
        weighted_median = value;
        break;
      }
    }
    const double limit = std::max(0.15, 4.0 * 1.4826 * weighted_median);
    plane.inliers = 0;
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      inlier[n] = weight[n] > 0.0 && deviation[n] <= limit;
      if (inlier[n]) {
        sum_squares += weight[n] * deviation[n] * deviation[n];
        sum_weights += weight[n];
        ++plane.inliers;
      }
    }
    plane.rms = sum_weights > 0.0 ? std::sqrt(sum_squares / sum_weights) : 0.0;
  }
  plane.k = {k.x + dkx, k.y + dky};
  // phase(p) = offset + 2 pi dk . (p - centre) + 2 pi k . p  =  2 pi (k + dk) . p + [offset - 2 pi dk . centre].
  plane.offset = Wrap(offset - kTwoPi * (dkx * centre_x + dky * centre_y));
  return plane;
}

// Step 3: the hexagonal lattice of two reciprocal vectors and a lens position. The row direction is the shortest
// lattice vector nearest the rotation hint (horizontal by default: both Lytro cameras have horizontal lens rows).
HexLattice LatticeFromReciprocal(const Frequency& k1, const Frequency& k2, double lens_x, double lens_y,
                                 double rotation_hint) {
  // Direct basis a1, a2 with k_i . a_j = delta_ij: the columns of [k1; k2]^-1.
  Eigen::Matrix2d reciprocal;
  reciprocal << k1.x, k1.y, k2.x, k2.y;
  const Eigen::Matrix2d direct = reciprocal.inverse();
  const Eigen::Vector2d a1 = direct.col(0), a2 = direct.col(1);
  std::vector<Eigen::Vector2d> shortest = {a1, a2, a1 + a2, a1 - a2};
  std::sort(shortest.begin(), shortest.end(),
            [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return p.squaredNorm() < q.squaredNorm(); });
  shortest.resize(3);
  Eigen::Vector2d along = shortest[0];
  double best = 1e9;
  for (Eigen::Vector2d candidate : shortest) {
    if (candidate.x() < 0.0) candidate = -candidate;
    const double difference = std::abs(Wrap(std::atan2(candidate.y(), candidate.x()) - rotation_hint));
    if (difference < best) {
      best = difference;
      along = candidate;
    }
  }
  // The model's columns stand perpendicular to its rows; a real lattice's may lean a little (the F01's centre table and
  // its frames: the columns 1.1e-4 rad off the rows' normal). The rows' angle alone would put all of that lean into the
  // columns, whose ends then sit 0.18 px off at the top and bottom of the sensor; the mean of the two angles halves it
  // at both. A column runs from a lens to the one two rows on: twice the step to its neighbour half a pitch ahead in
  // the next row, minus the step along the row.
  Eigen::Vector2d column(-along.y(), along.x());  // perpendicular, should no such neighbour be found
  const double cell = std::abs(direct.determinant());
  for (Eigen::Vector2d candidate : shortest) {
    if (along.x() * candidate.y() - along.y() * candidate.x() < 0.0) candidate = -candidate;  // into the next row
    if (along.x() * candidate.y() - along.y() * candidate.x() > 0.5 * cell && candidate.dot(along) > 0.0)
      column = 2.0 * candidate - along;
  }
  const double row_angle = std::atan2(along.y(), along.x());
  const double column_angle = std::atan2(column.y(), column.x()) - 0.5 * std::numbers::pi;
  HexLattice lattice;
  lattice.rotation = row_angle + 0.5 * Wrap(column_angle - row_angle);
  lattice.spacing_x = along.norm();
  // Row spacing: the area of the lattice cell divided by the pitch along a row.
  lattice.spacing_y = std::abs(direct.determinant()) / lattice.spacing_x;
  lattice.origin_x = lens_x;
  lattice.origin_y = lens_y;
  return lattice;
}

}  // namespace

GridEstimate EstimateLensletGridFromCapture(const cv::Mat& grey, const std::optional<GridGuess>& guess) {
  if (grey.type() != CV_32FC1 || grey.empty())
    throw Error("lenslet grid: the image must be a non-empty single-channel float image");
  const bool hinted = guess && guess->spacing > 0.0;
  if (hinted && !(guess->spacing >= 3.0 && guess->spacing <= 200.0))
    throw Error("lenslet grid: spacing hint " + std::to_string(guess->spacing) + " px is out of range");
  const double min_spacing = hinted ? 0.85 * guess->spacing : 4.0;
  const double max_spacing = hinted ? 1.15 * guess->spacing : std::min(60.0, std::min(grey.cols, grey.rows) / 6.0);
  if (std::min(grey.cols, grey.rows) < 6 * max_spacing)
    throw Error("lenslet grid: the image is smaller than 6 micro-lenses across");

  // 1. Coarse reciprocal vectors (the contrast's window follows the spacing once it is known).
  cv::Mat contrast = LocalContrast(grey, hinted ? guess->spacing : 0.5 * (min_spacing + max_spacing));
  std::array<Frequency, 2> coarse = CoarseReciprocal(contrast, min_spacing, max_spacing);
  const double spacing = 1.0 / (kHalfSqrt3 * coarse[0].Norm());
  if (!hinted) {
    contrast = LocalContrast(grey, spacing);
    coarse = CoarseReciprocal(contrast, 0.85 * spacing, 1.15 * spacing);
  }

  // 2. Block phases at k1, k2 and k3 = k2 - k1 (the third first-ring vector), a phase plane through each.
  std::array<Frequency, 3> k = {coarse[0], coarse[1], Frequency{coarse[1].x - coarse[0].x, coarse[1].y - coarse[0].y}};
  const int block = std::clamp(static_cast<int>(std::lround(12.0 * spacing)), 32, std::min(grey.cols, grey.rows));
  std::array<PhasePlane, 3> planes;
  int columns = 0, rows = 0;
  // Blocks tile the sensor; on small images they overlap by half, for enough of them.
  const int step = (grey.cols / block) * (grey.rows / block) >= 100 ? block : block / 2;
  // Two rounds: the second demodulates at the refined vectors (the coarse ones can be a fraction of a spectrum bin
  // off, which on small images is a noticeable phase drift across a block).
  for (int round = 0; round < 2; ++round) {
    const std::vector<BlockPhases> blocks = DemodulateBlocks(contrast, k, block, step, columns, rows);
    for (int m = 0; m < 3; ++m) planes[m] = FitPhasePlane(blocks, m, k[m], columns, rows, step);
    // The three vectors are not independent (k3 = k2 - k1): average the two estimates of each.
    k[0] = {0.5 * (planes[0].k.x + planes[1].k.x - planes[2].k.x),
            0.5 * (planes[0].k.y + planes[1].k.y - planes[2].k.y)};
    k[1] = {0.5 * (planes[1].k.x + planes[0].k.x + planes[2].k.x),
            0.5 * (planes[1].k.y + planes[0].k.y + planes[2].k.y)};
    k[2] = {k[1].x - k[0].x, k[1].y - k[0].y};
  }

  // A lens centre: phase_m(p) = 2 pi k_m . (p - centre) + psi, where psi (0 or pi, the sign of the micro-image
  // profile's Fourier coefficient) is the closure phase offset_1 - offset_2 + offset_3. The lens taken is the one
  // nearest the axis, in the middle of the blocks the planes were fitted to: each plane's phase there is its best
  // measured, where its phase at pixel (0, 0) is an extrapolation with its own vector, which the averaged vectors of
  // the lattice then carry back with the difference (0.2 px on the real F01 frames). From the middle, what the model
  // cannot follow (the columns' lean) is also half as large at the edges as from a corner.
  const double closure = Wrap(planes[0].offset - planes[1].offset + planes[2].offset);
  const double psi = std::abs(closure) > 0.5 * std::numbers::pi ? std::numbers::pi : 0.0;
  const double axis_x = guess && guess->axis_x > 0.0 ? guess->axis_x : 0.5 * (grey.cols - 1);
  const double axis_y = guess && guess->axis_y > 0.0 ? guess->axis_y : 0.5 * (grey.rows - 1);
  Eigen::Matrix2d reciprocal;
  reciprocal << k[0].x, k[0].y, k[1].x, k[1].y;
  auto phase_at_axis = [&](int m) {  // the fitted plane's own phase there
    return planes[m].offset + kTwoPi * (planes[m].k.x * axis_x + planes[m].k.y * axis_y);
  };
  const Eigen::Vector2d cycles(Wrap(psi - phase_at_axis(0)) / kTwoPi, Wrap(psi - phase_at_axis(1)) / kTwoPi);
  const Eigen::Vector2d lens = Eigen::Vector2d(axis_x, axis_y) + reciprocal.inverse() * cycles;

  const double rotation_hint = guess ? guess->rotation : 0.0;
  HexLattice lattice = LatticeFromReciprocal(k[0], k[1], lens.x(), lens.y(), rotation_hint);
  GridEstimate estimate;
  estimate.grid = GridFromLattice(lattice, axis_x, axis_y, grey.cols, grey.rows);
  // Fit quality in pixels: a phase error of e rad at first-ring frequency |k| moves the lattice by e / (2 pi |k|).
  double position_rms = 0.0;
  for (int m = 0; m < 3; ++m) {
    const double px = planes[m].rms / (kTwoPi * planes[m].k.Norm());
    position_rms += px * px / 3.0;
  }
  estimate.grid.rms_residual = std::sqrt(position_rms);
  estimate.grid.fit_method = "capture periodicity";
  estimate.grid.blocks_used = std::min({planes[0].inliers, planes[1].inliers, planes[2].inliers});
  estimate.grid.blocks = columns * rows;
  return estimate;
}

}  // namespace lfsp::decode
