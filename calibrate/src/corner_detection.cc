// Corner detection in every view of a capture: one full search, then tracking from view to view (see corners.h).

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "lfsp/calibrate/corners.h"
#include "lfsp/core/error.h"
#include "saddle_refinement.h"

namespace lfsp::calibrate {
namespace {

constexpr int kReferenceCandidates = 6;  // central views tried for the full search before giving up

// Median distance between horizontally adjacent corners: the square size in pixels.
double SquarePixels(const std::vector<cv::Point2d>& corners, int corners_x) {
  std::vector<double> d;
  for (std::size_t n = 0; n + 1 < corners.size(); ++n)
    if ((static_cast<int>(n) + 1) % corners_x != 0) d.push_back(cv::norm(corners[n + 1] - corners[n]));
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

// Full-image search for the board with the sector-based detector (Duda & Frese 2018).
bool FindBoard(const cv::Mat& grey, int corners_x, int corners_y, std::vector<cv::Point2d>& corners) {
  cv::Mat grey8;
  cv::normalize(grey, grey8, 0, 255, cv::NORM_MINMAX, CV_8U);
  std::vector<cv::Point2f> found;
  const cv::Size pattern(corners_x, corners_y);
  bool ok = cv::findChessboardCornersSB(grey8, pattern, found, cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY);
  if (!ok) {
    ok = cv::findChessboardCornersSB(grey8, pattern, found,
                                     cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY | cv::CALIB_CB_EXHAUSTIVE);
  }
  if (!ok || found.size() != static_cast<std::size_t>(corners_x * corners_y)) return false;
  corners.assign(found.begin(), found.end());
  return true;
}

// The whole visible part of a board that may overflow the image (CALIB_CB_LARGER from a 3 x 3 pattern), with its
// size. Rows and columns that come within `edge` pixels of the image border are trimmed.
bool FindVisibleBoard(const cv::Mat& grey, std::vector<cv::Point2d>& corners, int& corners_x, int& corners_y) {
  cv::Mat grey8;
  cv::normalize(grey, grey8, 0, 255, cv::NORM_MINMAX, CV_8U);
  std::vector<cv::Point2f> found;
  cv::Mat meta;
  const int flags =
      cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_ACCURACY | cv::CALIB_CB_LARGER | cv::CALIB_CB_EXHAUSTIVE;
  if (!cv::findChessboardCornersSB(grey8, cv::Size(3, 3), found, flags, meta)) return false;
  // meta is one entry per corner, rows x columns of the detected grid.
  corners_x = meta.cols;
  corners_y = meta.rows;
  if (corners_x < 3 || corners_y < 3 || found.size() != static_cast<std::size_t>(corners_x * corners_y)) return false;
  corners.assign(found.begin(), found.end());
  return true;
}

// Drops outer rows and columns of a full grid while any of their corners lies within `edge` px of the image border.
void TrimNearBorder(std::vector<cv::Point2d>& corners, int& corners_x, int& corners_y, int width, int height,
                    double edge) {
  auto near_border = [&](const cv::Point2d& p) {
    return p.x < edge || p.y < edge || p.x > width - 1 - edge || p.y > height - 1 - edge;
  };
  int x0 = 0, x1 = corners_x - 1, y0 = 0, y1 = corners_y - 1;
  auto at = [&](int a, int b) { return corners[static_cast<std::size_t>(b * corners_x + a)]; };
  for (bool changed = true; changed && x1 - x0 >= 2 && y1 - y0 >= 2;) {
    changed = false;
    auto column_near = [&](int a) {
      for (int b = y0; b <= y1; ++b)
        if (near_border(at(a, b))) return true;
      return false;
    };
    auto row_near = [&](int b) {
      for (int a = x0; a <= x1; ++a)
        if (near_border(at(a, b))) return true;
      return false;
    };
    if (column_near(x0)) ++x0, changed = true;
    if (column_near(x1)) --x1, changed = true;
    if (row_near(y0)) ++y0, changed = true;
    if (row_near(y1)) --y1, changed = true;
  }
  std::vector<cv::Point2d> kept;
  for (int b = y0; b <= y1; ++b)
    for (int a = x0; a <= x1; ++a) kept.push_back(at(a, b));
  corners = std::move(kept);
  corners_x = x1 - x0 + 1;
  corners_y = y1 - y0 + 1;
}

// Sub-pixel refinement: cornerSubPix (a window well inside one square) brings the prediction to within a fraction
// of a pixel, the saddle fit removes its pixel-grid bias (saddle_refinement.h).
void RefineCorners(const cv::Mat& grey, std::vector<cv::Point2d>& corners, double square_px) {
  const int half = std::clamp(static_cast<int>(0.42 * square_px), 2, 8);
  std::vector<cv::Point2f> points(corners.begin(), corners.end());
  cv::cornerSubPix(grey, points, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 60, 1e-4));
  for (std::size_t n = 0; n < points.size(); ++n) corners[n] = points[n];
  RefineCornersAtSaddles(grey, corners, SaddleSigma(square_px));
}

// RMS distance between `corners` and the homography image of `reference` that fits them best.
double GridResidual(const std::vector<cv::Point2d>& reference, const std::vector<cv::Point2d>& corners) {
  const cv::Mat h = cv::findHomography(reference, corners, 0);
  if (h.empty()) return 1e9;
  std::vector<cv::Point2d> mapped;
  cv::perspectiveTransform(reference, mapped, h);
  double sum = 0;
  for (std::size_t n = 0; n < corners.size(); ++n) sum += std::pow(cv::norm(mapped[n] - corners[n]), 2);
  return std::sqrt(sum / static_cast<double>(corners.size()));
}

void ReadCameraFacts(const Metadata& metadata, CaptureCorners& out) {
  if (!metadata.is_object() || !metadata.contains("camera") || !metadata["camera"].is_object()) return;
  const auto& camera = metadata["camera"];
  if (camera.contains("model") && camera["model"].is_string()) out.camera_model = camera["model"].get<std::string>();
  if (camera.contains("serial") && camera["serial"].is_string()) out.serial = camera["serial"].get<std::string>();
  if (camera.contains("zoom_step") && camera["zoom_step"].is_number()) out.zoom_step = camera["zoom_step"].get<int>();
  if (camera.contains("focus_step") && camera["focus_step"].is_number())
    out.focus_step = camera["focus_step"].get<int>();
}

}  // namespace

cv::Mat GreyView(const LightField& light_field, ViewIndex view) {
  const cv::Mat colour = light_field.View(view);
  if (colour.channels() == 1) return colour.clone();
  cv::Mat grey(colour.rows, colour.cols, CV_32F);
  const int channels = colour.channels();
  for (int y = 0; y < colour.rows; ++y) {
    const float* in = colour.ptr<float>(y);
    float* out = grey.ptr<float>(y);
    for (int x = 0; x < colour.cols; ++x) {
      float sum = 0;
      for (int c = 0; c < channels; ++c) sum += in[x * channels + c];
      out[x] = sum / static_cast<float>(channels);
    }
  }
  return grey;
}

std::vector<double> ViewWeights(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  std::vector<double> weights(shape.Views(), 0.0);
  for (int cam = 0; cam < static_cast<int>(shape.Views()); ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    const cv::Mat m = light_field.HasWeights() ? cv::Mat(shape.height, shape.width, CV_32F,
                                                         const_cast<float*>(light_field.weights().ViewData(view)))
                                               : light_field.View(view);
    const cv::Scalar mean = cv::mean(m);
    double sum = 0;
    for (int c = 0; c < m.channels(); ++c) sum += mean[c];
    weights[static_cast<std::size_t>(cam)] = sum / m.channels();
  }
  if (!light_field.HasWeights()) {
    const double brightest = *std::max_element(weights.begin(), weights.end());
    if (brightest > 0)
      for (double& w : weights) w /= brightest;
  }
  return weights;
}

namespace {

// The view border CornerDetectionOptions::view_border asks for on this light field (resolving -1, automatic).
int ViewBorderFor(const LightField& light_field, int requested) {
  if (requested >= 0) return requested;
  return DecodedFromSensor(light_field) ? 1 : 0;
}

// 1 for each view (row-major cam order) within `border` view steps (Euclidean) of a dark view or of a position
// outside the view grid: the rim of the micro-lens image.
std::vector<char> LensletEdgeViews(const LightFieldShape& shape, const std::vector<double>& weights,
                                   double min_view_weight, int border) {
  std::vector<char> at_edge(shape.Views(), 0);
  const auto outside_lens = [&](int u, int v) {
    if (u < 0 || v < 0 || u >= shape.nu || v >= shape.nv) return true;
    return weights[static_cast<std::size_t>(CameraNumber({u, v}, shape.nu))] < min_view_weight;
  };
  for (int cam = 0; cam < static_cast<int>(shape.Views()); ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    for (int dv = -border; dv <= border && !at_edge[static_cast<std::size_t>(cam)]; ++dv)
      for (int du = -border; du <= border; ++du)
        if (du * du + dv * dv <= border * border && outside_lens(view.u + du, view.v + dv)) {
          at_edge[static_cast<std::size_t>(cam)] = 1;
          break;
        }
  }
  return at_edge;
}

}  // namespace

bool CanonicalCornerOrder(std::vector<cv::Point2d>& corners, int corners_x, int corners_y) {
  if (corners.size() != static_cast<std::size_t>(corners_x * corners_y) || corners_x < 2 || corners_y < 2) return false;
  const auto at = [&](const std::vector<cv::Point2d>& grid, int nx, int a, int b) {
    return grid[static_cast<std::size_t>(b * nx + a)];
  };
  double best_score = -2.0;
  std::vector<cv::Point2d> best;
  // Candidate re-indexings (a', b') -> (a, b): optional transpose (square grids only) and flips of either axis.
  for (int transpose = 0; transpose < (corners_x == corners_y ? 2 : 1); ++transpose) {
    for (int flip_a = 0; flip_a < 2; ++flip_a) {
      for (int flip_b = 0; flip_b < 2; ++flip_b) {
        std::vector<cv::Point2d> grid(corners.size());
        for (int b = 0; b < corners_y; ++b) {
          for (int a = 0; a < corners_x; ++a) {
            int sa = flip_a ? corners_x - 1 - a : a;
            int sb = flip_b ? corners_y - 1 - b : b;
            if (transpose) std::swap(sa, sb);
            grid[static_cast<std::size_t>(b * corners_x + a)] = at(corners, corners_x, sa, sb);
          }
        }
        cv::Point2d along(0, 0), down(0, 0);
        for (int b = 0; b < corners_y; ++b) along += at(grid, corners_x, corners_x - 1, b) - at(grid, corners_x, 0, b);
        for (int a = 0; a < corners_x; ++a) down += at(grid, corners_x, a, corners_y - 1) - at(grid, corners_x, a, 0);
        const double cross = along.x * down.y - along.y * down.x;
        const double length = cv::norm(along);
        if (cross <= 0 || length == 0) continue;  // mirrored: the board frame would be left-handed
        const double score = along.x / length;    // closest to the image's +x direction wins
        if (score > best_score) {
          best_score = score;
          best = std::move(grid);
        }
      }
    }
  }
  if (best.empty()) return false;
  corners = std::move(best);
  return true;
}

CaptureCorners DetectCaptureCorners(const LightField& light_field, const std::string& name,
                                    const CornerDetectionOptions& options) {
  const LightFieldShape& shape = light_field.shape();
  if (light_field.empty()) throw Error(name + ": the light field is empty");
  const bool partial = options.corners_x == 0 && options.corners_y == 0;
  if (!partial && (options.corners_x < 3 || options.corners_y < 3))
    throw Error("checkerboard size " + std::to_string(options.corners_x) + "x" + std::to_string(options.corners_y) +
                ": at least 3x3 inner corners are needed");
  CaptureCorners out;
  out.name = name;
  out.shape = shape;
  out.corners_x = options.corners_x;
  out.corners_y = options.corners_y;
  out.partial_board = partial;
  ReadCameraFacts(light_field.metadata, out);

  const int views = static_cast<int>(shape.Views());
  const std::vector<double> weights = ViewWeights(light_field);
  const std::vector<char> at_edge =
      LensletEdgeViews(shape, weights, options.min_view_weight, ViewBorderFor(light_field, options.view_border));
  std::vector<char> usable(static_cast<std::size_t>(views), 0);
  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (weights[static_cast<std::size_t>(cam)] < options.min_view_weight) {
      out.dark_views.push_back(view);
    } else if (at_edge[static_cast<std::size_t>(cam)]) {
      out.edge_views.push_back(view);
    } else {
      usable[static_cast<std::size_t>(cam)] = 1;
    }
  }

  // Full search in the central usable views, nearest the centre first.
  const ViewIndex centre = shape.Centre();
  std::vector<int> candidates;
  for (int cam = 0; cam < views; ++cam)
    if (usable[static_cast<std::size_t>(cam)]) candidates.push_back(cam);
  if (candidates.empty())
    throw Error(name + ": no usable view (every view's mean weight is below " +
                std::to_string(options.min_view_weight) + ")");
  const auto centre_distance = [&](int cam) {
    const ViewIndex v = ViewFromCameraNumber(cam, shape.nu);
    return (v.u - centre.u) * (v.u - centre.u) + (v.v - centre.v) * (v.v - centre.v);
  };
  std::stable_sort(candidates.begin(), candidates.end(),
                   [&](int a, int b) { return centre_distance(a) < centre_distance(b); });
  std::vector<cv::Point2d> reference_corners;
  int reference = -1;
  for (std::size_t c = 0; c < candidates.size() && c < static_cast<std::size_t>(kReferenceCandidates); ++c) {
    const ViewIndex view = ViewFromCameraNumber(candidates[c], shape.nu);
    const cv::Mat grey = GreyView(light_field, view);
    bool found_board = false;
    if (partial) {
      found_board = FindVisibleBoard(grey, reference_corners, out.corners_x, out.corners_y) &&
                    CanonicalCornerOrder(reference_corners, out.corners_x, out.corners_y);
      if (found_board) {
        TrimNearBorder(reference_corners, out.corners_x, out.corners_y, shape.width, shape.height,
                       SquarePixels(reference_corners, out.corners_x) + 2.0);
        found_board = out.corners_x >= 3 && out.corners_y >= 3;
      }
    } else {
      found_board = FindBoard(grey, options.corners_x, options.corners_y, reference_corners) &&
                    CanonicalCornerOrder(reference_corners, options.corners_x, options.corners_y);
    }
    if (found_board) {
      reference = candidates[c];
      break;
    }
  }
  if (reference < 0 && partial)
    throw Error(name +
                ": no checkerboard (of any size, at least 3x3 inner corners away from the edges) found in the "
                "central views");
  if (reference < 0) {
    std::ostringstream message;
    message << name << ": no checkerboard of " << options.corners_x << "x" << options.corners_y
            << " inner corners found in the central views (is the grid size right? it counts inner corners, "
               "one less than the squares per side)";
    throw Error(message.str());
  }
  out.reference = ViewFromCameraNumber(reference, shape.nu);
  const double square_px = SquarePixels(reference_corners, out.corners_x);
  RefineCorners(GreyView(light_field, out.reference), reference_corners, square_px);

  // Track the corners ring by ring away from the reference view.
  std::vector<std::vector<cv::Point2d>> found(static_cast<std::size_t>(views));
  std::vector<char> failed(static_cast<std::size_t>(views), 0);
  found[static_cast<std::size_t>(reference)] = reference_corners;
  const auto ring = [&](int cam) {
    const ViewIndex v = ViewFromCameraNumber(cam, shape.nu);
    return std::max(std::abs(v.u - out.reference.u), std::abs(v.v - out.reference.v));
  };
  const auto detected = [&](int u, int v) {
    return u >= 0 && v >= 0 && u < shape.nu && v < shape.nv &&
           !found[static_cast<std::size_t>(CameraNumber({u, v}, shape.nu))].empty();
  };
  const int rings =
      std::max({out.reference.u, shape.nu - 1 - out.reference.u, out.reference.v, shape.nv - 1 - out.reference.v});
  for (int r = 1; r <= rings; ++r) {
    std::vector<int> todo;
    for (int cam = 0; cam < views; ++cam)
      if (ring(cam) == r && usable[static_cast<std::size_t>(cam)]) todo.push_back(cam);
#pragma omp parallel for schedule(dynamic)
    for (std::size_t t = 0; t < todo.size(); ++t) {
      const int cam = todo[t];
      const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
      // Nearest detected neighbour in the previous ring (4-neighbours before diagonals).
      int best_u = -1, best_v = -1, best_d = 3;
      for (int dv = -1; dv <= 1; ++dv)
        for (int du = -1; du <= 1; ++du) {
          const int nu = view.u + du, nv = view.v + dv;
          if ((du == 0 && dv == 0) || !detected(nu, nv)) continue;
          if (ring(CameraNumber({nu, nv}, shape.nu)) != r - 1) continue;
          const int d = std::abs(du) + std::abs(dv);
          if (d < best_d) {
            best_d = d;
            best_u = nu;
            best_v = nv;
          }
        }
      if (best_u < 0) {
        failed[static_cast<std::size_t>(cam)] = 1;
        continue;
      }
      const auto& near = found[static_cast<std::size_t>(CameraNumber({best_u, best_v}, shape.nu))];
      std::vector<cv::Point2d> predicted = near;
      // The board moves linearly with the view index (disparity): extrapolate from the view beyond the neighbour.
      const int far_u = 2 * best_u - view.u, far_v = 2 * best_v - view.v;
      if (detected(far_u, far_v) && ring(CameraNumber({far_u, far_v}, shape.nu)) < r) {
        const auto& far = found[static_cast<std::size_t>(CameraNumber({far_u, far_v}, shape.nu))];
        for (std::size_t n = 0; n < predicted.size(); ++n) predicted[n] = 2.0 * near[n] - far[n];
      }
      std::vector<cv::Point2d> corners = predicted;
      bool inside = true;
      const double margin = 0.5 * square_px + 2;
      for (const auto& p : corners)
        inside =
            inside && p.x > margin && p.y > margin && p.x < shape.width - 1 - margin && p.y < shape.height - 1 - margin;
      if (!inside) {
        failed[static_cast<std::size_t>(cam)] = 1;
        continue;
      }
      RefineCorners(GreyView(light_field, view), corners, square_px);
      double worst_move = 0;
      for (std::size_t n = 0; n < corners.size(); ++n)
        worst_move = std::max(worst_move, cv::norm(corners[n] - predicted[n]));
      if (worst_move > 0.4 * square_px || GridResidual(reference_corners, corners) > options.max_grid_residual) {
        failed[static_cast<std::size_t>(cam)] = 1;
        continue;
      }
      found[static_cast<std::size_t>(cam)] = std::move(corners);
    }
  }

  for (int cam = 0; cam < views; ++cam) {
    const ViewIndex view = ViewFromCameraNumber(cam, shape.nu);
    if (!found[static_cast<std::size_t>(cam)].empty()) {
      out.views.push_back({view, std::move(found[static_cast<std::size_t>(cam)])});
    } else if (usable[static_cast<std::size_t>(cam)]) {
      out.failed_views.push_back(view);
    }
  }
  return out;
}

}  // namespace lfsp::calibrate
