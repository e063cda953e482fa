// Checkerboard light fields in decoded geometry (see checkerboard.h for the ray model).
//
// Each view is rendered by following the ray of every integer sample index to the board plane. Edges are
// anti-aliased analytically: the signed distance from a pixel to the nearest checker line, measured in pixels
// through the local Jacobian of the index -> board mapping, goes through an erf profile whose width combines the
// optical blur, the defocus of the board (which grows with its disparity) and the pixel footprint. The pattern is
// point-symmetric about every corner, so a corner detector sees the true corner, as with a real sharp print.

#include "lfsp/simulate/checkerboard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "lfsp/core/error.h"

namespace lfsp::simulate {
namespace {

constexpr double kBlack = 0.08;       // albedo of the printed squares
constexpr double kWhite = 0.85;       // paper
constexpr double kBackground = 0.30;  // beyond the paper

struct Ray {
  double origin[3];
  double direction[3];
};

struct Rotation {
  double m[3][3];
};

Rotation RotationFromAngleAxis(const std::array<double, 3>& r) {
  const double angle = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  Rotation rot{};
  if (angle < 1e-15) {
    for (int a = 0; a < 3; ++a) rot.m[a][a] = 1.0;
    return rot;
  }
  const double x = r[0] / angle, y = r[1] / angle, z = r[2] / angle;
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  rot.m[0][0] = t * x * x + c;
  rot.m[0][1] = t * x * y - s * z;
  rot.m[0][2] = t * x * z + s * y;
  rot.m[1][0] = t * x * y + s * z;
  rot.m[1][1] = t * y * y + c;
  rot.m[1][2] = t * y * z - s * x;
  rot.m[2][0] = t * x * z - s * y;
  rot.m[2][1] = t * y * z + s * x;
  rot.m[2][2] = t * z * z + c;
  return rot;
}

// The physical ray of sample index (i, j, k, l) in the camera frame: H n, then distortion of the direction.
Ray PhysicalRay(const CheckerboardCamera& camera, double i, double j, double k, double l) {
  const auto& h = camera.h;
  double phi[4];
  for (int r = 0; r < 4; ++r)
    phi[r] = h[5 * r] * i + h[5 * r + 1] * j + h[5 * r + 2] * k + h[5 * r + 3] * l + h[5 * r + 4];
  const auto& d = camera.distortion;
  const double du = phi[2] - d[3], dv = phi[3] - d[4];
  const double r2 = du * du + dv * dv;
  const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[2]));
  return {{phi[0], phi[1], 0.0}, {radial * du + d[3], radial * dv + d[4], 1.0}};
}

// Where a camera-frame ray meets the board plane z = 0 of the board frame: board (x, y) and the camera depth.
struct BoardHit {
  double x = 0, y = 0, depth = 0;
  bool valid = false;
};

class BoardGeometry {
 public:
  explicit BoardGeometry(const BoardPose& pose)
      : rotation_(RotationFromAngleAxis(pose.rotation)), t_(pose.translation) {}

  BoardHit Intersect(const Ray& ray) const {
    double o[3], d[3];  // ray in the board frame: R^T (origin - t), R^T direction
    for (int a = 0; a < 3; ++a) {
      o[a] = 0;
      d[a] = 0;
      for (int b = 0; b < 3; ++b) {
        o[a] += rotation_.m[b][a] * (ray.origin[b] - t_[static_cast<std::size_t>(b)]);
        d[a] += rotation_.m[b][a] * ray.direction[b];
      }
    }
    BoardHit hit;
    if (std::abs(d[2]) < 1e-12) return hit;
    const double lambda = -o[2] / d[2];
    if (lambda <= 0) return hit;
    hit.x = o[0] + lambda * d[0];
    hit.y = o[1] + lambda * d[1];
    hit.depth = ray.origin[2] + lambda * ray.direction[2];
    hit.valid = true;
    return hit;
  }

 private:
  Rotation rotation_;
  std::array<double, 3> t_;
};

// Smoothed step across a line: 0.5 (1 + erf(distance / (sqrt(2) sigma))), exact 0/1 far from the line.
double SmoothStep(double distance_px, double sigma) {
  const double z = distance_px / (std::sqrt(2.0) * sigma);
  if (z > 3.5) return 1.0;
  if (z < -3.5) return 0.0;
  return 0.5 * (1.0 + std::erf(z));
}

// Smoothed square wave along one board axis: +1 in even squares, -1 in odd ones.
double SquareWave(double coordinate, double square, double metres_per_pixel, double sigma) {
  const double m = std::round(coordinate / square);
  const double distance_px = (coordinate - m * square) / metres_per_pixel;
  const double sign = (static_cast<long long>(m) % 2 == 0) ? 1.0 : -1.0;
  return sign * (2.0 * SmoothStep(distance_px, sigma) - 1.0);
}

// Smoothed indicator of the interval [lo, hi] along one board axis.
double Inside(double coordinate, double lo, double hi, double metres_per_pixel, double sigma) {
  return SmoothStep((coordinate - lo) / metres_per_pixel, sigma) *
         SmoothStep((hi - coordinate) / metres_per_pixel, sigma);
}

// Vignetting of a whole view: 1 inside the main-lens aperture, falling to a dark floor for views outside it.
double ViewWeight(const CheckerboardCaptureOptions& options, int u, int v) {
  const auto& cam = options.camera;
  const double du = u - (cam.nu - 1) / 2.0, dv = v - (cam.nv - 1) / 2.0;
  const double rho = std::sqrt(du * du + dv * dv) / (0.5 * std::max(cam.nu, cam.nv));
  double w = std::clamp((options.aperture_radius - rho) / 0.2, 0.0, 1.0);
  w = w * w * (3.0 - 2.0 * w);
  return 0.02 + 0.98 * w;
}

std::array<double, 25> RecentredH(double h11, double h13, double h31, double h33, double h22, double h24, double h42,
                                  double h44, int nu, int nv, int width, int height) {
  std::array<double, 25> h{};
  h[0] = h11;
  h[2] = h13;
  h[6] = h22;
  h[8] = h24;
  h[10] = h31;
  h[12] = h33;
  h[16] = h42;
  h[18] = h44;
  h[24] = 1.0;
  const double ic = (width - 1) / 2.0, jc = (height - 1) / 2.0, kc = (nu - 1) / 2.0, lc = (nv - 1) / 2.0;
  for (int r = 0; r < 4; ++r)
    h[5 * r + 4] = -(h[5 * r] * ic + h[5 * r + 1] * jc + h[5 * r + 2] * kc + h[5 * r + 3] * lc);
  return h;
}

void CheckOptions(const CheckerboardCaptureOptions& o) {
  const auto& c = o.camera;
  if (c.nu < 1 || c.nv < 1 || c.width < 16 || c.height < 16) throw Error("checkerboard capture: camera size too small");
  if (o.corners_x < 2 || o.corners_y < 2) throw Error("checkerboard capture: the board needs at least 2x2 corners");
  if (!(o.square_size > 0)) throw Error("checkerboard capture: square_size must be positive");
  if (o.channels != 1 && o.channels != 3) throw Error("checkerboard capture: channels must be 1 or 3");
  if (!(o.blur > 0)) throw Error("checkerboard capture: blur must be positive");
}

}  // namespace

CheckerboardCamera IllumCheckerboardCamera(double scale) {
  CheckerboardCamera c;
  c.name = "illum";
  c.nu = c.nv = 15;
  c.width = static_cast<int>(std::lround(625 * scale));
  c.height = static_cast<int>(std::lround(434 * scale));
  const double pixel = 1.2e-3 / scale;  // ray direction per pixel (rad)
  const double baseline = 9.0e-4;       // m per view step on the s, t plane (aperture ~ 13 mm)
  c.focal_plane = 0.25;
  c.h = RecentredH(0, baseline, pixel, -baseline / c.focal_plane, 0, baseline * 1.004, pixel * 1.006,
                   -baseline * 1.004 / c.focal_plane, c.nu, c.nv, c.width, c.height);
  c.distortion = {0.08, -0.05, 0.0, 1.5e-3, -1.0e-3};
  return c;
}

CheckerboardCamera F01CheckerboardCamera(int views, double scale) {
  CheckerboardCamera c;
  c.name = "f01";
  c.nu = c.nv = views;
  c.width = c.height = static_cast<int>(std::lround(380 * scale));
  const double pixel = 1.85e-3 / scale;
  const double baseline = 3.2e-3 / views;  // aperture of a 6.45 mm f/2 lens over the views
  c.focal_plane = 0.2;
  c.h = RecentredH(0, baseline, pixel, -baseline / c.focal_plane, 0, baseline, pixel * 1.003, -baseline / c.focal_plane,
                   c.nu, c.nv, c.width, c.height);
  c.distortion = {0.15, -0.10, 0.0, -1.0e-3, 2.0e-3};
  return c;
}

bool ProjectBoardPoint(const CheckerboardCamera& camera, const BoardPose& pose, double x, double y, int u, int v,
                       PixelPosition& pixel) {
  const BoardGeometry board(pose);
  double i = (camera.width - 1) / 2.0, j = (camera.height - 1) / 2.0;
  constexpr double kStep = 1e-3;
  for (int iteration = 0; iteration < 50; ++iteration) {
    const BoardHit h0 = board.Intersect(PhysicalRay(camera, i, j, u, v));
    const BoardHit hi = board.Intersect(PhysicalRay(camera, i + kStep, j, u, v));
    const BoardHit hj = board.Intersect(PhysicalRay(camera, i, j + kStep, u, v));
    if (!h0.valid || !hi.valid || !hj.valid) return false;
    const double a = (hi.x - h0.x) / kStep, b = (hj.x - h0.x) / kStep;
    const double c = (hi.y - h0.y) / kStep, d = (hj.y - h0.y) / kStep;
    const double det = a * d - b * c;
    if (std::abs(det) < 1e-30) return false;
    const double ex = x - h0.x, ey = y - h0.y;
    double di = (d * ex - b * ey) / det, dj = (-c * ex + a * ey) / det;
    const double length = std::hypot(di, dj);
    if (length > 50) {  // damp the first steps from the view centre
      di *= 50 / length;
      dj *= 50 / length;
    }
    i += di;
    j += dj;
    if (length < 1e-7) break;
  }
  const BoardHit check = board.Intersect(PhysicalRay(camera, i, j, u, v));
  if (!check.valid || std::hypot(check.x - x, check.y - y) > 1e-9) return false;
  if (i < 0 || j < 0 || i > camera.width - 1 || j > camera.height - 1) return false;
  pixel = {static_cast<float>(i), static_cast<float>(j)};
  return true;
}

CheckerboardCapture RenderCheckerboardLightField(const CheckerboardCaptureOptions& options) {
  CheckOptions(options);
  const CheckerboardCamera& cam = options.camera;
  LightFieldShape shape{cam.nu, cam.nv, cam.width, cam.height, options.channels};
  CheckerboardCapture out;
  out.pose = options.pose;
  out.light_field = LightField(shape);
  out.light_field.transfer = Transfer::kLinear;
  out.light_field.EnableWeights(1.0f);
  const BoardGeometry board(options.pose);
  const double sq = options.square_size;
  const double cx = options.corners_x * sq, cy = options.corners_y * sq;
  const double disparity_per_inverse_depth = cam.h[2] / cam.h[10];  // H13 / H31: disparity = this * (1/Z - 1/Zf)
  const int w = cam.width, h = cam.height;
  const int views = cam.nu * cam.nv;

#pragma omp parallel for schedule(dynamic)
  for (int cam_index = 0; cam_index < views; ++cam_index) {
    const ViewIndex view = ViewFromCameraNumber(cam_index, cam.nu);
    // Board hits at the integer sample positions (one extra row and column for forward differences).
    std::vector<BoardHit> hits(static_cast<std::size_t>(w + 1) * static_cast<std::size_t>(h + 1));
    for (int y = 0; y <= h; ++y)
      for (int x = 0; x <= w; ++x)
        hits[static_cast<std::size_t>(y) * static_cast<std::size_t>(w + 1) + static_cast<std::size_t>(x)] =
            board.Intersect(PhysicalRay(cam, x, y, view.u, view.v));
    const double view_weight = ViewWeight(options, view.u, view.v);
    std::mt19937_64 rng(options.seed * 1000003ULL + static_cast<std::uint64_t>(cam_index));
    std::normal_distribution<double> normal(0.0, 1.0);
    float* pixels = out.light_field.ViewData(view);
    float* weights = out.light_field.weights().ViewData(view);
    const double half_diagonal2 = 0.25 * (static_cast<double>(w) * w + static_cast<double>(h) * h);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const auto at = [&](int xx, int yy) -> const BoardHit& {
          return hits[static_cast<std::size_t>(yy) * static_cast<std::size_t>(w + 1) + static_cast<std::size_t>(xx)];
        };
        const BoardHit& p = at(x, y);
        const BoardHit& px = at(x + 1, y);
        const BoardHit& py = at(x, y + 1);
        double albedo = kBackground;
        if (p.valid && px.valid && py.valid) {
          // Metres on the board per pixel across lines of constant board x (resp. y).
          const double gx = std::max(std::hypot(px.x - p.x, py.x - p.x), 1e-12);
          const double gy = std::max(std::hypot(px.y - p.y, py.y - p.y), 1e-12);
          const double disparity = disparity_per_inverse_depth * (1.0 / p.depth - 1.0 / cam.focal_plane);
          const double defocus = options.defocus_blur * disparity;
          const double sigma = std::sqrt(options.blur * options.blur + defocus * defocus + 1.0 / 12.0);
          const double paper = Inside(p.x, -2 * sq, cx + sq, gx, sigma) * Inside(p.y, -2 * sq, cy + sq, gy, sigma);
          const double pattern = Inside(p.x, -sq, cx, gx, sigma) * Inside(p.y, -sq, cy, gy, sigma);
          double checker = kWhite;
          if (pattern > 0) {
            const double cell = 0.5 + 0.5 * SquareWave(p.x, sq, gx, sigma) * SquareWave(p.y, sq, gy, sigma);
            checker = kBlack + (kWhite - kBlack) * cell;
          }
          albedo = kBackground + paper * (kWhite - kBackground) + pattern * (checker - kWhite);
        }
        const double dx = x - (w - 1) / 2.0, dy = y - (h - 1) / 2.0;
        const double weight = view_weight * (1.0 - 0.25 * (dx * dx + dy * dy) / half_diagonal2);
        const double mean = albedo * weight;
        const double sigma_noise =
            std::sqrt(options.read_noise * options.read_noise + mean / std::max(options.photons_at_white, 1.0));
        const std::size_t pixel =
            static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
        for (int c = 0; c < options.channels; ++c) {
          const double value = mean + sigma_noise * normal(rng);
          pixels[pixel * static_cast<std::size_t>(options.channels) + static_cast<std::size_t>(c)] =
              static_cast<float>(std::clamp(value, 0.0, 1.0));
        }
        weights[pixel] = static_cast<float>(weight);
      }
    }
  }

  // Ground-truth corners in every view.
  const int corners = options.corners_x * options.corners_y;
  out.corners.assign(static_cast<std::size_t>(views),
                     std::vector<PixelPosition>(static_cast<std::size_t>(corners),
                                                PixelPosition{std::numeric_limits<float>::quiet_NaN(),
                                                              std::numeric_limits<float>::quiet_NaN()}));
#pragma omp parallel for schedule(dynamic)
  for (int cam_index = 0; cam_index < views; ++cam_index) {
    const ViewIndex view = ViewFromCameraNumber(cam_index, cam.nu);
    for (int b = 0; b < options.corners_y; ++b)
      for (int a = 0; a < options.corners_x; ++a) {
        PixelPosition pixel;
        if (ProjectBoardPoint(cam, options.pose, a * sq, b * sq, view.u, view.v, pixel))
          out.corners[static_cast<std::size_t>(cam_index)][static_cast<std::size_t>(b * options.corners_x + a)] = pixel;
      }
  }

  auto& meta = out.light_field.metadata;
  meta["camera"] = {{"model", cam.name == "f01" ? "F01" : "ILLUM"},
                    {"serial", options.serial},
                    {"zoom_step", options.zoom_step},
                    {"focus_step", options.focus_step}};
  meta["simulate"]["checkerboard"] = {{"camera", cam.name},
                                      {"H", cam.h},
                                      {"distortion", cam.distortion},
                                      {"corners", {options.corners_x, options.corners_y}},
                                      {"square_size", sq},
                                      {"rotation", options.pose.rotation},
                                      {"translation", options.pose.translation}};
  return out;
}

std::vector<BoardPose> CalibrationPoses(const CheckerboardCamera& camera, int count, std::uint32_t seed, int corners_x,
                                        int corners_y, double square_size) {
  if (count < 1) throw Error("CalibrationPoses: count must be at least 1");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double pixel_x = camera.h[10], pixel_y = camera.h[16];  // rad per pixel
  // Distance at which the board with its margins spans `fill` of the smaller field of view.
  const double board_w = (corners_x + 3) * square_size, board_h = (corners_y + 3) * square_size;
  const double fov_x = camera.width * pixel_x, fov_y = camera.height * pixel_y;
  const double fit = std::max(board_w / fov_x, board_h / fov_y);
  std::vector<BoardPose> poses;
  const double pi = std::acos(-1.0);
  for (int n = 0; n < count; ++n) {
    const double fill = 0.52 + 0.18 * uniform(rng);
    const double distance = fit / fill;
    const double tilt = (15.0 + 25.0 * uniform(rng)) * pi / 180.0;
    const double axis_angle = 2 * pi * (n + 0.3 * uniform(rng)) / count;  // tilt axes spread around the circle
    const double spin = (-15.0 + 30.0 * uniform(rng)) * pi / 180.0;
    // Tilt about an in-plane axis, then turn about the optical axis: combine as angle-axis via rotation matrices.
    const std::array<double, 3> tilt_aa{tilt * std::cos(axis_angle), tilt * std::sin(axis_angle), 0.0};
    const Rotation a = RotationFromAngleAxis(tilt_aa);
    const Rotation b = RotationFromAngleAxis({0.0, 0.0, spin});
    Rotation r{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
    // Back to angle-axis.
    const double cos_angle = std::clamp((r.m[0][0] + r.m[1][1] + r.m[2][2] - 1.0) / 2.0, -1.0, 1.0);
    const double angle = std::acos(cos_angle);
    std::array<double, 3> aa{0, 0, 0};
    if (angle > 1e-12) {
      const double f = angle / (2.0 * std::sin(angle));
      aa = {f * (r.m[2][1] - r.m[1][2]), f * (r.m[0][2] - r.m[2][0]), f * (r.m[1][0] - r.m[0][1])};
    }
    // Move the board centre off the optical axis, towards a corner of the view (the corners of the field of view
    // are where the distortion is strongest), keeping the board with its margins inside the view.
    const double span_x = board_w / (distance * fov_x), span_y = board_h / (distance * fov_y);
    const double centre_x = (uniform(rng) - 0.5) * 0.7 * (1.0 - span_x) * fov_x * distance;
    const double centre_y = (uniform(rng) - 0.5) * 0.7 * (1.0 - span_y) * fov_y * distance;
    const double bx = (corners_x - 1) * square_size / 2.0, by = (corners_y - 1) * square_size / 2.0;
    BoardPose pose;
    pose.rotation = aa;
    for (int i = 0; i < 3; ++i) {
      const double centre = i == 0 ? centre_x : (i == 1 ? centre_y : distance);
      pose.translation[static_cast<std::size_t>(i)] = centre - (r.m[i][0] * bx + r.m[i][1] * by);
    }
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace lfsp::simulate
