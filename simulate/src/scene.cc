#include "lfsp/simulate/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "json_fields.h"
#include "lfsp/core/error.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/untrusted_json.h"

namespace lfsp::simulate {

std::array<float, 3> BoardToCamera(const Board& board, float bx, float by) {
  // Rodrigues: R = I cos(a) + (1 - cos(a)) k k^T + sin(a) [k]x, with a = |r|, k = r / a.
  const double rx = board.rotation[0], ry = board.rotation[1], rz = board.rotation[2];
  const double a = std::sqrt(rx * rx + ry * ry + rz * rz);
  double p[3] = {bx, by, 0.0};
  double out[3] = {p[0], p[1], p[2]};
  if (a > 1e-12) {
    const double k[3] = {rx / a, ry / a, rz / a};
    const double c = std::cos(a), s = std::sin(a);
    const double kp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
    const double cross[3] = {k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]};
    for (int i = 0; i < 3; ++i) out[i] = p[i] * c + cross[i] * s + k[i] * kp * (1 - c);
  }
  return {static_cast<float>(out[0] + board.translation[0]), static_cast<float>(out[1] + board.translation[1]),
          static_cast<float>(out[2] + board.translation[2])};
}

std::vector<std::array<float, 3>> BoardCornersInCamera(const Board& board, bool outline) {
  std::vector<std::array<float, 3>> corners;
  if (outline) {
    // The outer edge of the white border, one square around the squares.
    const float m = board.square;
    const float w = board.cols * board.square, h = board.rows * board.square;
    for (const auto& [bx, by] : {std::pair{-m, -m}, {w + m, -m}, {w + m, h + m}, {-m, h + m}})
      corners.push_back(BoardToCamera(board, bx, by));
    return corners;
  }
  for (int l = 1; l < board.rows; ++l)
    for (int k = 1; k < board.cols; ++k)
      corners.push_back(
          BoardToCamera(board, static_cast<float>(k) * board.square, static_cast<float>(l) * board.square));
  return corners;
}

namespace {

// A bar from `a` to `b` of the given width (fraction of min(width, height)) as a 4-point polygon. The width is
// applied in normalised units of the shorter side, so for non-square images it is exact only along the axes;
// that is fine for occluders, whose ground truth comes from the polygon actually rendered.
std::vector<std::array<float, 2>> BarPolygon(std::array<float, 2> a, std::array<float, 2> b, float width) {
  const float dx = b[0] - a[0];
  const float dy = b[1] - a[1];
  const float length = std::hypot(dx, dy);
  if (length <= 0.0f) return {a, a, a};
  const float nx = -dy / length * width * 0.5f;
  const float ny = dx / length * width * 0.5f;
  return {{a[0] + nx, a[1] + ny}, {b[0] + nx, b[1] + ny}, {b[0] - nx, b[1] - ny}, {a[0] - nx, a[1] - ny}};
}

Shape ShapeFromJson(const nlohmann::json& json, const std::string& where) {
  Shape shape;
  const std::string type = RequireString(json, "type", where);
  if (type == "everywhere") {
    shape.kind = Shape::Kind::kEverywhere;
  } else if (type == "rect") {
    shape.kind = Shape::Kind::kRect;
    shape.points = {ReadPoint(json.value("min", nlohmann::json()), where + ".min"),
                    ReadPoint(json.value("max", nlohmann::json()), where + ".max")};
    if (!(shape.points[0][0] < shape.points[1][0] && shape.points[0][1] < shape.points[1][1]))
      throw Error(where + ": rect needs min < max in x and y");
  } else if (type == "polygon") {
    shape.kind = Shape::Kind::kPolygon;
    if (!json.contains("points") || !json.at("points").is_array() || json.at("points").size() < 3)
      throw Error(where + ".points: expected at least 3 [x, y] points");
    for (std::size_t i = 0; i < json.at("points").size(); ++i)
      shape.points.push_back(ReadPoint(json.at("points")[i], where + ".points[" + std::to_string(i) + "]"));
  } else if (type == "bar") {
    shape.kind = Shape::Kind::kPolygon;
    const float width = ReadFloat(json, "width", 0.01f, where);
    if (!(width > 0.0f)) throw Error(where + ".width: must be > 0");
    shape.points = BarPolygon(ReadPoint(json.value("from", nlohmann::json()), where + ".from"),
                              ReadPoint(json.value("to", nlohmann::json()), where + ".to"), width);
  } else if (type == "disc") {
    shape.kind = Shape::Kind::kDisc;
    shape.centre = ReadPoint(json, "centre", shape.centre, where);
    shape.radius = ReadFloat(json, "radius", shape.radius, where);
    if (!(shape.radius > 0.0f)) throw Error(where + ".radius: must be > 0");
  } else {
    throw Error(where + ".type: unknown shape '" + type + "' (expected everywhere, rect, polygon, bar or disc)");
  }
  return shape;
}

nlohmann::json ShapeToJson(const Shape& shape) {
  nlohmann::json json;
  switch (shape.kind) {
    case Shape::Kind::kEverywhere:
      json["type"] = "everywhere";
      break;
    case Shape::Kind::kRect:
      json["type"] = "rect";
      json["min"] = shape.points[0];
      json["max"] = shape.points[1];
      break;
    case Shape::Kind::kPolygon:
      json["type"] = "polygon";
      json["points"] = shape.points;
      break;
    case Shape::Kind::kDisc:
      json["type"] = "disc";
      json["centre"] = shape.centre;
      json["radius"] = shape.radius;
      break;
  }
  return json;
}

SceneObject ObjectFromJson(const nlohmann::json& json, int index, const std::string& base_dir,
                           const std::string& where) {
  if (!json.is_object()) throw Error(where + ": expected an object");
  SceneObject object;
  object.name = json.value("name", "object" + std::to_string(index));
  if (json.contains("label")) {
    if (!json.at("label").is_number_integer() || json.at("label").get<long long>() < 0 ||
        json.at("label").get<long long>() > 1000000)
      throw Error(where + ".label: expected an integer in 0..1000000");
    object.label = json.at("label").get<int>();
  } else {
    object.label = index;
  }
  const std::string type = json.value("type", std::string("plane"));
  object.disparity = ReadFloat(json, "disparity", 0.0f, where);
  if (type == "plane") {
    object.geometry = SceneObject::Geometry::kPlane;
    object.shape = ShapeFromJson(json.value("shape", nlohmann::json{{"type", "everywhere"}}), where + ".shape");
    object.slope = ReadPoint(json, "slope", object.slope, where);
    object.pivot = ReadPoint(json, "pivot", object.pivot, where);
  } else if (type == "ellipsoid" || type == "sphere") {
    object.geometry = SceneObject::Geometry::kEllipsoid;
    object.centre = ReadPoint(json, "centre", object.centre, where);
    object.radius = ReadFloat(json, "radius", object.radius, where);
    object.bulge = ReadFloat(json, "bulge", object.bulge, where);
    if (!(object.radius > 0.0f)) throw Error(where + ".radius: must be > 0");
    if (!(object.bulge > 0.0f)) throw Error(where + ".bulge: must be > 0 (use a disc-shaped plane for a flat disc)");
  } else if (type == "board") {
    object.geometry = SceneObject::Geometry::kBoard;
    Board& board = object.board;
    board.rows = static_cast<int>(ReadFloat(json, "rows", static_cast<float>(board.rows), where));
    board.cols = static_cast<int>(ReadFloat(json, "cols", static_cast<float>(board.cols), where));
    board.square = ReadFloat(json, "square", board.square, where);
    if (board.rows < 2 || board.cols < 2 || board.rows > 100 || board.cols > 100)
      throw Error(where + ": board rows and cols must be 2..100");
    if (!(board.square > 0.0f)) throw Error(where + ".square: must be > 0");
    for (const char* key : {"rotation", "translation"}) {
      if (!json.contains(key)) continue;
      const auto& v = json.at(key);
      if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
        throw Error(where + "." + key + ": expected [x, y, z]");
      auto& target = std::string(key) == "rotation" ? board.rotation : board.translation;
      for (int k = 0; k < 3; ++k)
        target[static_cast<std::size_t>(k)] =
            CheckedNumber(v[static_cast<std::size_t>(k)], where + "." + key + "[" + std::to_string(k) + "]");
    }
    if (!(board.translation[2] > 0.0f)) throw Error(where + ".translation: the board must be in front (z > 0)");
    object.texture.kind = Texture::Kind::kChecker;
    return object;
  } else {
    throw Error(where + ".type: unknown object type '" + type + "' (expected plane, ellipsoid or board)");
  }
  if (!json.contains("texture")) throw Error(where + ".texture: missing");
  object.texture = TextureFromJson(json.at("texture"), base_dir, where + ".texture");
  if (json.contains("specular")) {
    const auto& spec = json.at("specular");
    const std::string w = where + ".specular";
    Specular specular;
    specular.centre = ReadPoint(spec, "centre", specular.centre, w);
    specular.radius = ReadFloat(spec, "radius", specular.radius, w);
    specular.strength = ReadFloat(spec, "strength", specular.strength, w);
    specular.shift = ReadFloat(spec, "shift", specular.shift, w);
    if (!(specular.radius > 0.0f)) throw Error(w + ".radius: must be > 0");
    object.specular = specular;
  }
  return object;
}

// Disparity bounds of one object over its support (planes with unbounded support use the image square).
std::array<float, 2> ObjectDisparityRange(const SceneObject& object, const PinholeRig& rig) {
  if (object.geometry == SceneObject::Geometry::kBoard) {
    std::array<float, 2> range{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
    for (const auto& corner : BoardCornersInCamera(object.board, true)) {
      const float d = rig.Disparity(corner[2]);
      range = {std::min(range[0], d), std::max(range[1], d)};
    }
    return range;
  }
  if (object.geometry == SceneObject::Geometry::kEllipsoid) return {object.disparity, object.disparity + object.bulge};
  std::vector<std::array<float, 2>> corners;
  switch (object.shape.kind) {
    case Shape::Kind::kEverywhere:
      corners = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
      break;
    case Shape::Kind::kRect: {
      const auto& p = object.shape.points;
      corners = {p[0], {p[1][0], p[0][1]}, {p[0][0], p[1][1]}, p[1]};
      break;
    }
    case Shape::Kind::kPolygon:
      corners = object.shape.points;
      break;
    case Shape::Kind::kDisc: {
      const auto& c = object.shape.centre;
      const float r = object.shape.radius;
      corners = {{c[0] - r, c[1] - r}, {c[0] + r, c[1] - r}, {c[0] - r, c[1] + r}, {c[0] + r, c[1] + r}};
      break;
    }
  }
  float lo = std::numeric_limits<float>::max();
  float hi = std::numeric_limits<float>::lowest();
  for (const auto& p : corners) {
    const float d =
        object.disparity + object.slope[0] * (p[0] - object.pivot[0]) + object.slope[1] * (p[1] - object.pivot[1]);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return {lo, hi};
}

}  // namespace

std::array<float, 2> Scene::DisparityRange() const {
  std::array<float, 2> range{std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()};
  for (const auto& object : objects) {
    const auto r = ObjectDisparityRange(object, rig);
    range[0] = std::min(range[0], r[0]);
    range[1] = std::max(range[1], r[1]);
  }
  if (objects.empty()) range = {0.0f, 0.0f};
  return range;
}

int Scene::MaxLabel() const {
  int label = -1;
  for (const auto& object : objects) label = std::max(label, object.label);
  return label;
}

namespace {

Scene ParseScene(const nlohmann::json& json, const std::string& base_dir, const std::string& where) {
  if (!json.is_object()) throw Error(where + ": expected a JSON object with an \"objects\" array");
  Scene scene;
  scene.name = json.value("name", std::string("scene"));
  scene.description = json.value("description", std::string());
  if (json.contains("rig")) {
    const auto& rig = json.at("rig");
    const std::string w = where + ".rig";
    scene.rig.focal = ReadFloat(rig, "focal", scene.rig.focal, w);
    scene.rig.disparity_gain = ReadFloat(rig, "disparity_gain", scene.rig.disparity_gain, w);
    scene.rig.focus_distance = ReadFloat(rig, "focus_distance", scene.rig.focus_distance, w);
    if (!(scene.rig.focal > 0.0f && scene.rig.disparity_gain > 0.0f && scene.rig.focus_distance > 0.0f))
      throw Error(w + ": focal, disparity_gain and focus_distance must be > 0");
  }
  if (!json.contains("objects") || !json.at("objects").is_array() || json.at("objects").empty())
    throw Error(where + ".objects: expected a non-empty array");
  const auto& objects = json.at("objects");
  for (std::size_t i = 0; i < objects.size(); ++i)
    scene.objects.push_back(
        ObjectFromJson(objects[i], static_cast<int>(i), base_dir, where + ".objects[" + std::to_string(i) + "]"));
  return scene;
}

}  // namespace

Scene SceneFromJson(const nlohmann::json& json, const std::string& base_dir, const std::string& where) {
  try {
    return ParseScene(json, base_dir, where);
  } catch (const nlohmann::json::exception& e) {
    // A field of the wrong JSON type met by a typed accessor (e.g. "name": 3).
    throw Error(where + ": invalid field: " + e.what());
  }
}

Scene LoadScene(const std::filesystem::path& path) {
  const nlohmann::json json = ParseUntrustedJson(ReadWholeFile(path), path.string());
  return SceneFromJson(json, path.parent_path().string(), path.string());
}

nlohmann::json SceneToJson(const Scene& scene) {
  nlohmann::json json;
  json["name"] = scene.name;
  json["description"] = scene.description;
  json["rig"] = {{"focal", scene.rig.focal},
                 {"disparity_gain", scene.rig.disparity_gain},
                 {"focus_distance", scene.rig.focus_distance}};
  json["objects"] = nlohmann::json::array();
  for (const auto& object : scene.objects) {
    nlohmann::json o;
    o["name"] = object.name;
    o["label"] = object.label;
    o["disparity"] = object.disparity;
    if (object.geometry == SceneObject::Geometry::kBoard) {
      o["type"] = "board";
      o["rows"] = object.board.rows;
      o["cols"] = object.board.cols;
      o["square"] = object.board.square;
      o["rotation"] = object.board.rotation;
      o["translation"] = object.board.translation;
      json["objects"].push_back(o);
      continue;
    }
    if (object.geometry == SceneObject::Geometry::kPlane) {
      o["type"] = "plane";
      o["shape"] = ShapeToJson(object.shape);
      o["slope"] = object.slope;
      o["pivot"] = object.pivot;
    } else {
      o["type"] = "ellipsoid";
      o["centre"] = object.centre;
      o["radius"] = object.radius;
      o["bulge"] = object.bulge;
    }
    o["texture"] = TextureToJson(object.texture);
    if (object.specular) {
      o["specular"] = {{"centre", object.specular->centre},
                       {"radius", object.specular->radius},
                       {"strength", object.specular->strength},
                       {"shift", object.specular->shift}};
    }
    json["objects"].push_back(o);
  }
  return json;
}

Scene SceneFromSpec(const std::string& spec) {
  const auto names = BuiltinSceneNames();
  if (std::find(names.begin(), names.end(), spec) != names.end()) return BuiltinScene(spec);
  if (std::filesystem::exists(spec)) return LoadScene(spec);
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  throw Error("scene '" + spec + "': neither a built-in scene (" + list + ") nor an existing JSON file");
}

}  // namespace lfsp::simulate
