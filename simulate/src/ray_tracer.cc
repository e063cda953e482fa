#include "ray_tracer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lfsp/core/error.h"
#include "lfsp/core/srgb.h"

namespace lfsp::simulate {
namespace {

bool PointInPolygon(const std::vector<std::array<float, 2>>& polygon, float x, float y) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const auto& a = polygon[i];
    const auto& b = polygon[j];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) inside = !inside;
  }
  return inside;
}

}  // namespace

RayTracer::RayTracer(const Scene& scene, int width, int height, float disparity_scale, float max_view_offset,
                     Transfer transfer)
    : scene_(scene),
      width_(width),
      height_(height),
      min_side_(static_cast<float>(std::min(width, height))),
      transfer_(transfer) {
  const float w = static_cast<float>(width);
  const float h = static_cast<float>(height);
  const float k = disparity_scale;
  // Normalised coordinates map to pixels with centres at integers: X = x_n * W - 0.5.
  auto to_px = [&](const std::array<float, 2>& p) { return std::array<float, 2>{p[0] * w - 0.5f, p[1] * h - 0.5f}; };
  const float huge = 1e7f;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& object = scene.objects[i];
    Prepared p;
    p.source = static_cast<int>(i);
    p.label = object.label;
    p.geometry = object.geometry;
    if (object.geometry == SceneObject::Geometry::kBoard) {
      PrepareBoard(object, k, p);
    } else if (object.geometry == SceneObject::Geometry::kPlane) {
      p.support = object.shape.kind;
      p.b = k * object.slope[0] / w;
      p.c = k * object.slope[1] / h;
      p.a = k * (object.disparity + object.slope[0] * (0.5f / w - object.pivot[0]) +
                 object.slope[1] * (0.5f / h - object.pivot[1]));
      p.x0 = p.y0 = -huge;
      p.x1 = p.y1 = huge;
      switch (object.shape.kind) {
        case Shape::Kind::kEverywhere:
          break;
        case Shape::Kind::kRect:
        case Shape::Kind::kPolygon: {
          for (const auto& q : object.shape.points) p.polygon.push_back(to_px(q));
          if (object.shape.kind == Shape::Kind::kRect) {
            const auto lo = p.polygon[0];
            const auto hi = p.polygon[1];
            p.polygon = {lo, {hi[0], lo[1]}, hi, {lo[0], hi[1]}};
          }
          p.x0 = p.y0 = huge;
          p.x1 = p.y1 = -huge;
          for (const auto& q : p.polygon) {
            p.x0 = std::min(p.x0, q[0]);
            p.x1 = std::max(p.x1, q[0]);
            p.y0 = std::min(p.y0, q[1]);
            p.y1 = std::max(p.y1, q[1]);
          }
          break;
        }
        case Shape::Kind::kDisc: {
          const auto c = to_px(object.shape.centre);
          p.cx = c[0];
          p.cy = c[1];
          p.radius = object.shape.radius * min_side_;
          p.x0 = p.cx - p.radius;
          p.x1 = p.cx + p.radius;
          p.y0 = p.cy - p.radius;
          p.y1 = p.cy + p.radius;
          break;
        }
      }
    }
    if (object.geometry != SceneObject::Geometry::kEllipsoid) {
      // Disparity bounds over the (image-clipped) bounding box corners.
      const float bx0 = std::max(p.x0, -w), bx1 = std::min(p.x1, 2 * w);
      const float by0 = std::max(p.y0, -h), by1 = std::min(p.y1, 2 * h);
      p.dmin = std::numeric_limits<float>::max();
      p.dmax = std::numeric_limits<float>::lowest();
      for (float x : {bx0, bx1})
        for (float y : {by0, by1}) {
          const float d = p.a + p.b * x + p.c * y;
          p.dmin = std::min(p.dmin, d);
          p.dmax = std::max(p.dmax, d);
        }
    } else {
      const auto c = to_px(object.centre);
      p.cx = c[0];
      p.cy = c[1];
      p.radius = object.radius * min_side_;
      p.disparity = k * object.disparity;
      p.bulge = k * object.bulge;
      p.x0 = p.cx - p.radius;
      p.x1 = p.cx + p.radius;
      p.y0 = p.cy - p.radius;
      p.y1 = p.cy + p.radius;
      p.dmin = std::min(p.disparity, p.disparity + p.bulge);
      p.dmax = std::max(p.disparity, p.disparity + p.bulge);
    }
    objects_.push_back(std::move(p));
  }
  std::stable_sort(objects_.begin(), objects_.end(),
                   [](const Prepared& l, const Prepared& r) { return l.dmax > r.dmax; });
  prepared_of_.assign(objects_.size(), 0);
  for (std::size_t i = 0; i < objects_.size(); ++i)
    prepared_of_[static_cast<std::size_t>(objects_[i].source)] = static_cast<int>(i);
  fallback_disparity_ = k * scene.DisparityRange()[0];

  // Culling grid over view-pixel space, with a margin for rays that start outside the image.
  const float margin = 2.0f * max_view_offset * 4.0f + 32.0f;
  origin_x_ = -margin;
  origin_y_ = -margin;
  cells_x_ = static_cast<int>(std::ceil((w + 2 * margin) / static_cast<float>(cell_size_)));
  cells_y_ = static_cast<int>(std::ceil((h + 2 * margin) / static_cast<float>(cell_size_)));
  cells_.assign(static_cast<std::size_t>(cells_x_) * static_cast<std::size_t>(cells_y_), {});
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const Prepared& p = objects_[i];
    // Swept footprint: a point at (X, Y) with disparity d appears at X - s d for |s| <= max_view_offset.
    const float sweep = max_view_offset * std::max(std::abs(p.dmin), std::abs(p.dmax)) + 1.0f;
    const float fx0 = p.x0 - sweep, fx1 = p.x1 + sweep, fy0 = p.y0 - sweep, fy1 = p.y1 + sweep;
    const int cx0 = std::clamp(static_cast<int>(std::floor((fx0 - origin_x_) / cell_size_)), 0, cells_x_ - 1);
    const int cx1 = std::clamp(static_cast<int>(std::floor((fx1 - origin_x_) / cell_size_)), 0, cells_x_ - 1);
    const int cy0 = std::clamp(static_cast<int>(std::floor((fy0 - origin_y_) / cell_size_)), 0, cells_y_ - 1);
    const int cy1 = std::clamp(static_cast<int>(std::floor((fy1 - origin_y_) / cell_size_)), 0, cells_y_ - 1);
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx)
        cells_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(cells_x_) + static_cast<std::size_t>(cx)]
            .push_back(static_cast<int>(i));
  }
}

const std::vector<int>& RayTracer::CellObjects(float px, float py) const {
  const int cx = std::clamp(static_cast<int>(std::floor((px - origin_x_) / cell_size_)), 0, cells_x_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor((py - origin_y_) / cell_size_)), 0, cells_y_ - 1);
  return cells_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(cells_x_) + static_cast<std::size_t>(cx)];
}

bool RayTracer::Inside(const Prepared& p, float x, float y) const {
  switch (p.support) {
    case Shape::Kind::kEverywhere:
      return true;
    case Shape::Kind::kRect:
      return x >= p.polygon[0][0] && x < p.polygon[2][0] && y >= p.polygon[0][1] && y < p.polygon[2][1];
    case Shape::Kind::kPolygon:
      return x >= p.x0 && x <= p.x1 && y >= p.y0 && y <= p.y1 && PointInPolygon(p.polygon, x, y);
    case Shape::Kind::kDisc:
      return (x - p.cx) * (x - p.cx) + (y - p.cy) * (y - p.cy) < p.radius * p.radius;
  }
  return false;
}

bool RayTracer::Intersect(const Prepared& p, float px, float py, float s, float t, RayHit& hit) const {
  if (p.geometry != SceneObject::Geometry::kEllipsoid) {
    // d = a + b (px + s d) + c (py + t d)  =>  d (1 - b s - c t) = a + b px + c py.
    const float denominator = 1.0f - p.b * s - p.c * t;
    if (denominator <= 1e-6f) return false;
    const float d = (p.a + p.b * px + p.c * py) / denominator;
    const float x = px + s * d;
    const float y = py + t * d;
    if (!Inside(p, x, y)) return false;
    hit.disparity = d;
    hit.x = x;
    hit.y = y;
    return true;
  }
  // Ellipsoid ((X-cx)^2 + (Y-cy)^2) / r^2 + (d - dc)^2 / h^2 = 1; the front surface is the larger root.
  const float ex = px - p.cx;
  const float ey = py - p.cy;
  const float inv_r2 = 1.0f / (p.radius * p.radius);
  const float inv_h2 = 1.0f / (p.bulge * p.bulge);
  const float qa = (s * s + t * t) * inv_r2 + inv_h2;
  const float qb = 2.0f * (ex * s + ey * t) * inv_r2 - 2.0f * p.disparity * inv_h2;
  const float qc = (ex * ex + ey * ey) * inv_r2 + p.disparity * p.disparity * inv_h2 - 1.0f;
  const float discriminant = qb * qb - 4.0f * qa * qc;
  if (discriminant < 0.0f) return false;
  const float d = (-qb + std::sqrt(discriminant)) / (2.0f * qa);
  hit.disparity = d;
  hit.x = px + s * d;
  hit.y = py + t * d;
  return true;
}

RayHit RayTracer::Trace(float px, float py, float s, float t) const {
  RayHit best;
  best.disparity = std::numeric_limits<float>::lowest();
  RayHit candidate;
  for (const int i : CellObjects(px, py)) {
    const Prepared& p = objects_[static_cast<std::size_t>(i)];
    if (p.dmax <= best.disparity) break;  // sorted nearest-first: nothing further can be in front
    if (Intersect(p, px, py, s, t, candidate) && candidate.disparity > best.disparity) {
      best = candidate;
      best.object = p.source;
    }
  }
  if (best.object < 0) best.disparity = fallback_disparity_;
  return best;
}

Rgb RayTracer::Shade(const RayHit& hit, float s, float t) const {
  if (hit.object < 0) return {0.0f, 0.0f, 0.0f};
  const SceneObject& object = scene_.objects[static_cast<std::size_t>(hit.object)];
  if (object.geometry == SceneObject::Geometry::kBoard) {
    Rgb colour =
        ShadeBoard(objects_[static_cast<std::size_t>(prepared_of_[static_cast<std::size_t>(hit.object)])], hit);
    if (transfer_ == Transfer::kLinear)
      for (auto& c : colour) c = SrgbToLinearTabulated(c);
    return colour;
  }
  Rgb colour = object.texture.Evaluate((hit.x + 0.5f) / min_side_, (hit.y + 0.5f) / min_side_);
  if (object.specular) {
    const Specular& spec = *object.specular;
    const float hx = spec.centre[0] * static_cast<float>(width_) - 0.5f + spec.shift * min_side_ * s;
    const float hy = spec.centre[1] * static_cast<float>(height_) - 0.5f + spec.shift * min_side_ * t;
    const float r = spec.radius * min_side_;
    const float g =
        spec.strength * std::exp(-((hit.x - hx) * (hit.x - hx) + (hit.y - hy) * (hit.y - hy)) / (2.0f * r * r));
    for (auto& c : colour) c = std::min(1.0f, c + g);
  }
  if (transfer_ == Transfer::kLinear)
    for (auto& c : colour) c = SrgbToLinearTabulated(c);
  return colour;
}

void RayTracer::PrepareBoard(const SceneObject& object, float disparity_scale, Prepared& p) const {
  // A 3D plane n . P = c seen through the rig: 1/Z = (n . ray) / c with ray = ((x-cx)/f, (y-cy)/f, 1), so the
  // disparity d = fB (1/Z - 1/Z0) is affine in the centre-view pixel position (x, y).
  p.board = object.board;
  p.rig = scene_.rig;
  p.scale = disparity_scale;
  p.focal = scene_.rig.focal * static_cast<float>(width_);
  p.pcx = 0.5f * static_cast<float>(width_ - 1);
  p.pcy = 0.5f * static_cast<float>(height_ - 1);
  p.origin = BoardToCamera(object.board, 0.0f, 0.0f);
  const auto ex = BoardToCamera(object.board, 1.0f, 0.0f), ey = BoardToCamera(object.board, 0.0f, 1.0f);
  for (int i = 0; i < 3; ++i) {
    p.axis_x[static_cast<std::size_t>(i)] = ex[static_cast<std::size_t>(i)] - p.origin[static_cast<std::size_t>(i)];
    p.axis_y[static_cast<std::size_t>(i)] = ey[static_cast<std::size_t>(i)] - p.origin[static_cast<std::size_t>(i)];
  }
  std::array<double, 3> n{p.axis_x[1] * p.axis_y[2] - p.axis_x[2] * p.axis_y[1],
                          p.axis_x[2] * p.axis_y[0] - p.axis_x[0] * p.axis_y[2],
                          p.axis_x[0] * p.axis_y[1] - p.axis_x[1] * p.axis_y[0]};
  double c = n[0] * p.origin[0] + n[1] * p.origin[1] + n[2] * p.origin[2];
  if (c < 0) {
    for (auto& v : n) v = -v;
    c = -c;
  }
  const double fb = p.rig.disparity_gain, f = p.focal;
  p.a = static_cast<float>(disparity_scale *
                           (fb / c * (n[2] - n[0] * p.pcx / f - n[1] * p.pcy / f) - fb / p.rig.focus_distance));
  p.b = static_cast<float>(disparity_scale * fb * n[0] / (c * f));
  p.c = static_cast<float>(disparity_scale * fb * n[1] / (c * f));
  p.support = Shape::Kind::kPolygon;
  p.x0 = p.y0 = 1e30f;
  p.x1 = p.y1 = -1e30f;
  for (const auto& q : BoardCornersInCamera(object.board, true)) {
    if (!(q[2] > 0.0f)) throw Error("scene: board '" + object.name + "' reaches behind the camera");
    const float x = p.focal * q[0] / q[2] + p.pcx, y = p.focal * q[1] / q[2] + p.pcy;
    p.polygon.push_back({x, y});
    p.x0 = std::min(p.x0, x);
    p.x1 = std::max(p.x1, x);
    p.y0 = std::min(p.y0, y);
    p.y1 = std::max(p.y1, y);
  }
}

Rgb RayTracer::ShadeBoard(const Prepared& p, const RayHit& hit) const {
  const float d = p.scale != 0.0f ? hit.disparity / p.scale : hit.disparity;
  const float z = p.rig.Depth(d);
  const float point[3] = {(hit.x - p.pcx) / p.focal * z - p.origin[0], (hit.y - p.pcy) / p.focal * z - p.origin[1],
                          z - p.origin[2]};
  // Board coordinates: the axes are orthonormal (a rotation), so projecting on them inverts it.
  const float bx = point[0] * p.axis_x[0] + point[1] * p.axis_x[1] + point[2] * p.axis_x[2];
  const float by = point[0] * p.axis_y[0] + point[1] * p.axis_y[1] + point[2] * p.axis_y[2];
  const float w = static_cast<float>(p.board.cols) * p.board.square;
  const float h = static_cast<float>(p.board.rows) * p.board.square;
  if (bx < 0.0f || by < 0.0f || bx >= w || by >= h) return {0.95f, 0.95f, 0.95f};  // white border
  const long parity =
      (static_cast<long>(std::floor(bx / p.board.square)) + static_cast<long>(std::floor(by / p.board.square))) & 1L;
  return parity == 0 ? Rgb{0.05f, 0.05f, 0.05f} : Rgb{0.95f, 0.95f, 0.95f};
}

}  // namespace lfsp::simulate
