#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "lfsp/simulate/texture.h"

namespace lfsp::simulate {

// Scenes live in "disparity space": a surface point is given by where it appears in the centre view (normalised
// image coordinates, x and y in [0, 1] across the width and height) and by its disparity d in pixels per view step
// (docs/DESIGN.md convention: centre pixel (x, y) appears in view (u, v) at (x - (u-uc) d, y - (v-vc) d); positive d is
// in front of the focal plane). A pinhole camera grid maps 3D space to (x, y, d) projectively, so 3D planes are exactly
// the surfaces with d affine in (x, y), 3D rays are straight lines in (x, y, d), and ground truth is analytic.
// Lengths (disc radii, bar widths) are fractions of min(width, height) so round things stay round.

// Where a plane exists, as seen from the centre view.
struct Shape {
  enum class Kind { kEverywhere, kRect, kPolygon, kDisc };
  Kind kind = Kind::kEverywhere;
  std::vector<std::array<float, 2>> points;  // kRect: two corners; kPolygon: vertices (convex or not), normalised
  std::array<float, 2> centre{0.5f, 0.5f};   // kDisc
  float radius = 0.1f;                       // kDisc, fraction of min(width, height)
};

// A mirror-like highlight whose position moves with the view, so the surface is not Lambertian (reproduces the
// paper's specular limitation). Highlight centre in view offset (s, t) = centre + shift * (s, t) (normalised
// units per view step), Gaussian of the given radius, added to the texture colour.
struct Specular {
  std::array<float, 2> centre{0.5f, 0.5f};
  float radius = 0.05f;
  float strength = 0.8f;
  float shift = 0.02f;
};

// A pinhole camera grid behind the disparity space, for scenes placed in metres (calibration boards): view (s, t)
// is a pinhole at (s B, t B, 0) looking along +Z, focal length f = focal * width pixels, principal point at the image
// centre, images sheared so the plane Z = focus_distance has zero disparity: d = fB (1/Z - 1/focus_distance) with
// fB = disparity_gain (pixels * metres), independent of the rendered resolution like every scene disparity.
struct PinholeRig {
  float focal = 1.0f;           // focal length as a multiple of the image width
  float disparity_gain = 0.6f;  // fB, pixels per view step times metres
  float focus_distance = 0.5f;  // m

  float Disparity(float z) const { return disparity_gain * (1.0f / z - 1.0f / focus_distance); }
  float Depth(float disparity) const { return disparity_gain / (disparity + disparity_gain / focus_distance); }
};

// A planar checkerboard at a known pose: board point (bx, by, 0) (metres, origin at the top-left corner of the
// squares, x right, y down) is at camera point R(rotation) * (bx, by, 0) + translation. Rendered with a one-square
// white border. Its rows x cols squares have (rows-1) x (cols-1) inner corners.
struct Board {
  int rows = 6;
  int cols = 8;
  float square = 0.02f;                                    // m
  std::array<float, 3> rotation{0, 0, 0};                  // Rodrigues vector, radians
  std::array<float, 3> translation{-0.08f, -0.06f, 0.5f};  // m
};

// Camera coordinates (metres) of board point (bx, by, 0).
std::array<float, 3> BoardToCamera(const Board& board, float bx, float by);
// The inner corners, row by row ((rows-1) x (cols-1)), or with `outline` the 4 corners of the white border.
std::vector<std::array<float, 3>> BoardCornersInCamera(const Board& board, bool outline = false);

struct SceneObject {
  enum class Geometry { kPlane, kEllipsoid, kBoard };
  std::string name;
  int label = 0;  // ground-truth object label (>= 0)
  Geometry geometry = Geometry::kPlane;
  Texture texture;
  std::optional<Specular> specular;

  // kPlane: d(x, y) = disparity + slope[0] * (x - pivot[0]) + slope[1] * (y - pivot[1]), x, y normalised.
  Shape shape;
  float disparity = 0.0f;
  std::array<float, 2> slope{0.0f, 0.0f};
  std::array<float, 2> pivot{0.5f, 0.5f};

  // kEllipsoid (a "sphere" in disparity space): silhouette disc centre/radius as for Shape::kDisc, disparity at the
  // silhouette = `disparity`, at the front-most point = disparity + bulge.
  std::array<float, 2> centre{0.5f, 0.5f};
  float radius = 0.1f;
  float bulge = 0.5f;

  // kBoard: a checkerboard at a pose, seen through Scene::rig (texture unused).
  Board board;
};

struct Scene {
  std::string name;
  std::string description;
  std::vector<SceneObject> objects;  // the first object is usually a background plane covering everything
  PinholeRig rig;                    // used by boards (and to report metric intrinsics)

  // Range of disparities present (analytic bounds over all objects).
  std::array<float, 2> DisparityRange() const;
  int MaxLabel() const;
};

// Parses the JSON scene format (see simulate/README section in the report, and BuiltinScene() for examples).
// `base_dir` resolves relative image-texture paths. Throws lfsp::Error naming the file/field on bad input.
Scene SceneFromJson(const nlohmann::json& json, const std::string& base_dir = ".", const std::string& where = "scene");
Scene LoadScene(const std::filesystem::path& path);
nlohmann::json SceneToJson(const Scene& scene);

// Named built-in scenes:
//   "planes"       fronto-parallel and slanted textured patches at several depths, occluding each other (default)
//   "occluders"    fine occluders: thin bars and a branch in front of textured planes
//   "two-horses"   two objects of almost the same colour at different depths, one partly behind the other
//   "spheres"      ellipsoids ("spheres") and discs in front of a slanted floor
//   "specular"     planes with view-dependent highlights
//   "checkerboard" one fronto-parallel checkerboard (for calibration-style tests)
//   "comb", "layers" thin teeth, rails and pickets over fine textures (laid out for 512 x 512 views)
//   "bars"         1-12 px bars and stripes at several depths over three textured walls (512 x 512)
//   "sculpture"    smooth finely textured ellipsoids in front of a textured wall (512 x 512)
//   "leaves"       large smooth leaves in shade: the real F01 frames' JPEG colour bands (with --exposure 1.8
//                  --mosaic-jpeg 75; builtin_scenes.cc says how its colours were chosen)
Scene BuiltinScene(const std::string& name);
std::vector<std::string> BuiltinSceneNames();

// A scene from `spec`: a built-in name, or a path to a .json file.
Scene SceneFromSpec(const std::string& spec);

}  // namespace lfsp::simulate
