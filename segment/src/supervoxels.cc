// SLIC supervoxels (Achanta et al., the 3D variant of SLIC) over the views of a light field arranged as a video.
// OpenCV has no supervoxel method, so this is a plain k-means in (L, a, b, x, y, frame) with SLIC's local search:
// every voxel compares only the centres within one grid step in each direction.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "connectivity.h"
#include "lab_image.h"
#include "lfsp/core/error.h"
#include "lfsp/segment/baselines.h"
#include "lfsp/segment/params.h"

namespace lfsp::segment {
namespace {

struct Centre {
  double l = 0, a = 0, b = 0, x = 0, y = 0, t = 0;
};

struct Accumulator {
  double l = 0, a = 0, b = 0, x = 0, y = 0, t = 0;
  long long n = 0;
};

}  // namespace

Labels SlicSupervoxels(const LightField& light_field, ViewOrder order, const BaselineParams& params) {
  RequireSuperpixelSizeFits(params.size, light_field.shape(), "SLIC supervoxels");
  const LightFieldShape& shape = light_field.shape();
  const int frames = static_cast<int>(shape.Views());
  const int w = shape.width, h = shape.height;
  const int step = params.size;
  const int step_t = std::max(1, params.temporal_step > 0 ? params.temporal_step : params.size);
  // Frame number -> view, in the chosen order.
  std::vector<ViewIndex> frame_view(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    frame_view[static_cast<std::size_t>(f)] =
        order == ViewOrder::kRowFirst ? ViewIndex{f % shape.nu, f / shape.nu} : ViewIndex{f / shape.nv, f % shape.nv};
  }
  LabRays lab = LabOfLightField(light_field);
  auto lab_at = [&](int f, int y, int x) {
    const ViewIndex v = frame_view[static_cast<std::size_t>(f)];
    return lab.data() +
           ((static_cast<std::size_t>(v.v) * static_cast<std::size_t>(shape.nu) + static_cast<std::size_t>(v.u)) *
                shape.ViewPixels() +
            static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) *
               3;
  };

  // Seeds on a regular grid, cell centres.
  const int cells_x = std::max(1, (w + step - 1) / step), cells_y = std::max(1, (h + step - 1) / step);
  const int cells_t = std::max(1, (frames + step_t - 1) / step_t);
  std::vector<Centre> centres;
  for (int ct = 0; ct < cells_t; ++ct) {
    for (int cy = 0; cy < cells_y; ++cy) {
      for (int cx = 0; cx < cells_x; ++cx) {
        Centre c;
        c.x = std::min(w - 1, cx * step + step / 2);
        c.y = std::min(h - 1, cy * step + step / 2);
        c.t = std::min(frames - 1, ct * step_t + step_t / 2);
        const float* p = lab_at(static_cast<int>(c.t), static_cast<int>(c.y), static_cast<int>(c.x));
        c.l = p[0];
        c.a = p[1];
        c.b = p[2];
        centres.push_back(c);
      }
    }
  }
  const double spatial_weight = (params.supervoxel_compactness / step) * (params.supervoxel_compactness / step);
  const double temporal_weight = (params.supervoxel_compactness / step_t) * (params.supervoxel_compactness / step_t);

  Labels labels(shape);
  auto label_at = [&](int f, int y, int x) -> std::int32_t& {
    return labels.at(frame_view[static_cast<std::size_t>(f)], y, x);
  };
  const int iterations = std::max(1, params.supervoxel_iterations);
  for (int iteration = 0; iteration < iterations; ++iteration) {
    // Bucket the centres by the grid cell they now sit in, for the local search.
    std::vector<std::vector<int>> bucket(static_cast<std::size_t>(cells_x * cells_y * cells_t));
    auto cell_of = [&](const Centre& c) {
      const int bx = std::clamp(static_cast<int>(c.x) / step, 0, cells_x - 1);
      const int by = std::clamp(static_cast<int>(c.y) / step, 0, cells_y - 1);
      const int bt = std::clamp(static_cast<int>(c.t) / step_t, 0, cells_t - 1);
      return (bt * cells_y + by) * cells_x + bx;
    };
    for (std::size_t i = 0; i < centres.size(); ++i)
      bucket[static_cast<std::size_t>(cell_of(centres[i]))].push_back(static_cast<int>(i));

#pragma omp parallel for schedule(dynamic)
    for (int f = 0; f < frames; ++f) {
      const int ft = std::min(f / step_t, cells_t - 1);
      std::vector<int> near;
      for (int y = 0; y < h; ++y) {
        const int fy = std::min(y / step, cells_y - 1);
        for (int x = 0; x < w; ++x) {
          const int fx = std::min(x / step, cells_x - 1);
          const float* p = lab_at(f, y, x);
          double best = std::numeric_limits<double>::infinity();
          int best_label = 0;
          for (int bt = std::max(0, ft - 1); bt <= std::min(cells_t - 1, ft + 1); ++bt) {
            for (int by = std::max(0, fy - 1); by <= std::min(cells_y - 1, fy + 1); ++by) {
              for (int bx = std::max(0, fx - 1); bx <= std::min(cells_x - 1, fx + 1); ++bx) {
                for (int i : bucket[static_cast<std::size_t>((bt * cells_y + by) * cells_x + bx)]) {
                  const Centre& c = centres[static_cast<std::size_t>(i)];
                  const double dx = x - c.x, dy = y - c.y, dt = f - c.t;
                  if (std::abs(dx) > step || std::abs(dy) > step || std::abs(dt) > step_t) continue;  // SLIC window
                  const double dl = p[0] - c.l, da = p[1] - c.a, db = p[2] - c.b;
                  const double distance =
                      dl * dl + da * da + db * db + spatial_weight * (dx * dx + dy * dy) + temporal_weight * dt * dt;
                  if (distance < best) {
                    best = distance;
                    best_label = i;
                  }
                }
              }
            }
          }
          if (best == std::numeric_limits<double>::infinity()) {
            // No centre within the window (it drifted away): take the seed of this voxel's own cell.
            best_label = (ft * cells_y + fy) * cells_x + fx;
          }
          label_at(f, y, x) = best_label;
        }
      }
    }

    // Move every centre to the mean of its voxels.
    std::vector<Accumulator> sums(centres.size());
    for (int f = 0; f < frames; ++f) {
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          Accumulator& s = sums[static_cast<std::size_t>(label_at(f, y, x))];
          const float* p = lab_at(f, y, x);
          s.l += p[0];
          s.a += p[1];
          s.b += p[2];
          s.x += x;
          s.y += y;
          s.t += f;
          ++s.n;
        }
      }
    }
    for (std::size_t i = 0; i < centres.size(); ++i) {
      const Accumulator& s = sums[i];
      if (s.n == 0) continue;
      const double inv = 1.0 / static_cast<double>(s.n);
      centres[i] = {s.l * inv, s.a * inv, s.b * inv, s.x * inv, s.y * inv, s.t * inv};
    }
  }
  // Like SLIC's connectivity enforcement, per frame: stray pieces of a supervoxel join their neighbour.
#pragma omp parallel for schedule(dynamic)
  for (int f = 0; f < frames; ++f) {
    KeepLargestPieces(labels.ViewData(frame_view[static_cast<std::size_t>(f)]), w, h);
  }
  return labels;
}

}  // namespace lfsp::segment
