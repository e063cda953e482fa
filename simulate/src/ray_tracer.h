#pragma once

#include <array>
#include <vector>

#include "lfsp/core/light_field.h"
#include "lfsp/simulate/render.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::simulate {

// A scene laid out in one pixel frame (width x height centre-view pixels, disparities scaled), ready for fast ray
// queries. Rays are lines in (X, Y, d) space: the ray of view offset (s, t) through view pixel (px, py) is
// X = px + s d, Y = py + t d; the nearest surface is the one with the largest d. Pixel centres are at integers.
class RayTracer {
 public:
  // `max_view_offset` bounds |s| and |t| of the rays that will be traced (used to cull objects per screen cell).
  RayTracer(const Scene& scene, int width, int height, float disparity_scale, float max_view_offset, Transfer transfer);

  RayHit Trace(float px, float py, float s, float t) const;
  // The colour of a hit seen from view offset (s, t): texture plus any specular highlight, in the tracer's transfer.
  Rgb Shade(const RayHit& hit, float s, float t) const;
  int Label(int object) const {
    return object < 0 ? Labels::kUnlabelled : scene_.objects[static_cast<std::size_t>(object)].label;
  }
  float FallbackDisparity() const { return fallback_disparity_; }

 private:
  struct Prepared {
    int source = 0;  // index in Scene::objects
    int label = 0;
    SceneObject::Geometry geometry = SceneObject::Geometry::kPlane;
    Shape::Kind support = Shape::Kind::kEverywhere;
    float a = 0, b = 0, c = 0;                  // plane: d = a + b X + c Y (pixels)
    std::vector<std::array<float, 2>> polygon;  // plane support, pixels
    float cx = 0, cy = 0, radius = 0;           // disc support / ellipsoid silhouette, pixels
    float disparity = 0, bulge = 0;             // ellipsoid
    float x0 = 0, y0 = 0, x1 = 0, y1 = 0;       // centre-view bounding box, pixels
    float dmin = 0, dmax = 0;                   // disparity bounds
    // kBoard: the board's axes and origin in camera space, and the rig in this pixel frame.
    std::array<float, 3> axis_x{}, axis_y{}, origin{};
    float focal = 0, pcx = 0, pcy = 0, scale = 1;  // focal length and principal point, pixels
    PinholeRig rig;
    Board board;
  };
  void PrepareBoard(const SceneObject& object, float disparity_scale, Prepared& p) const;
  Rgb ShadeBoard(const Prepared& p, const RayHit& hit) const;
  bool Intersect(const Prepared& object, float px, float py, float s, float t, RayHit& hit) const;
  bool Inside(const Prepared& object, float x, float y) const;
  const std::vector<int>& CellObjects(float px, float py) const;

  const Scene& scene_;
  int width_;
  int height_;
  float min_side_;
  Transfer transfer_;
  float fallback_disparity_ = 0;
  std::vector<Prepared> objects_;  // sorted by dmax, nearest first
  std::vector<int> prepared_of_;   // Scene::objects index -> objects_ index
  int cell_size_ = 16;
  int cells_x_ = 0, cells_y_ = 0;
  float origin_x_ = 0, origin_y_ = 0;
  std::vector<std::vector<int>> cells_;
};

}  // namespace lfsp::simulate
