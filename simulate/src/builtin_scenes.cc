// The named built-in scenes, written in the same JSON form a user would write (so they double as examples).
#include <nlohmann/json.hpp>

#include "lfsp/core/error.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::simulate {
namespace {

using nlohmann::json;

json Noise(json a, json b, float period, int seed) {
  return {{"type", "noise"}, {"colours", {a, b}}, {"period", period}, {"seed", seed}};
}
json Checker(json a, json b, float period, float angle = 0.0f) {
  return {{"type", "checker"}, {"colours", {a, b}}, {"period", period}, {"angle", angle}};
}
json Stripes(json a, json b, float period, float angle) {
  return {{"type", "stripes"}, {"colours", {a, b}}, {"period", period}, {"angle", angle}};
}
json Rect(float x0, float y0, float x1, float y1) { return {{"type", "rect"}, {"min", {x0, y0}}, {"max", {x1, y1}}}; }
json Bar(float x0, float y0, float x1, float y1, float width) {
  return {{"type", "bar"}, {"from", {x0, y0}}, {"to", {x1, y1}}, {"width", width}};
}
json Plane(const std::string& name, int label, json shape, float disparity, json texture, json slope = {0.0f, 0.0f},
           json pivot = {0.5f, 0.5f}) {
  return {{"name", name},           {"label", label}, {"type", "plane"}, {"shape", shape},
          {"disparity", disparity}, {"slope", slope}, {"pivot", pivot},  {"texture", texture}};
}
json Background(float disparity, json texture) {
  return Plane("background", 0, {{"type", "everywhere"}}, disparity, texture);
}

json PlanesScene() {
  return {{"name", "planes"},
          {"description", "fronto-parallel and slanted textured patches at several depths, occluding each other"},
          {"objects",
           {Background(-1.2f, Noise({0.25, 0.35, 0.55}, {0.75, 0.8, 0.9}, 0.08f, 11)),
            Plane("floor", 1, Rect(0.0f, 0.62f, 1.0f, 1.0f), -0.9f, Checker({0.9, 0.85, 0.7}, {0.35, 0.3, 0.25}, 0.07f),
                  {0.0f, 3.6f}, {0.5f, 0.62f}),
            Plane("stripes", 2, Rect(0.08f, 0.12f, 0.42f, 0.55f), 0.25f,
                  Stripes({0.9, 0.3, 0.2}, {0.95, 0.9, 0.3}, 0.05f, 30.0f)),
            Plane("noise-card", 3, Rect(0.3f, 0.3f, 0.66f, 0.72f), 0.95f,
                  Noise({0.1, 0.5, 0.2}, {0.7, 0.95, 0.5}, 0.04f, 5)),
            Plane("slanted", 4, Rect(0.62f, 0.08f, 0.93f, 0.5f), -0.3f,
                  Noise({0.5, 0.2, 0.5}, {0.95, 0.7, 0.9}, 0.05f, 9), {2.4f, 0.0f}, {0.775f, 0.29f})}}};
}

json OccludersScene() {
  json objects = {Background(-0.9f, Noise({0.45, 0.55, 0.3}, {0.85, 0.8, 0.55}, 0.06f, 21)),
                  Plane("card", 1, Rect(0.15f, 0.2f, 0.85f, 0.75f), 0.1f,
                        Checker({0.85, 0.85, 0.9}, {0.2, 0.25, 0.45}, 0.09f, 15.0f))};
  // Thin vertical bars (about 1.5 px wide at 128 px) well in front.
  const float bar_x[3] = {0.27f, 0.5f, 0.71f};
  for (int i = 0; i < 3; ++i)
    objects.push_back(Plane("bar" + std::to_string(i), 2 + i, Bar(bar_x[i], 0.0f, bar_x[i] + 0.04f, 1.0f, 0.012f), 1.3f,
                            {{"type", "constant"}, {"colour", {0.55, 0.3, 0.15}}}));
  // A branch: one label, several slightly slanted segments with twigs.
  const json branch_texture = Noise({0.3, 0.2, 0.1}, {0.5, 0.38, 0.22}, 0.03f, 4);
  const float pts[5][2] = {{0.0f, 0.85f}, {0.22f, 0.72f}, {0.45f, 0.62f}, {0.7f, 0.42f}, {1.0f, 0.3f}};
  for (int i = 0; i < 4; ++i)
    objects.push_back(Plane("branch", 5, Bar(pts[i][0], pts[i][1], pts[i + 1][0], pts[i + 1][1], 0.02f), 0.8f,
                            branch_texture, {0.4f, 0.0f}, {0.5f, 0.5f}));
  objects.push_back(Plane("branch", 5, Bar(0.45f, 0.62f, 0.52f, 0.45f, 0.008f), 0.8f, branch_texture, {0.4f, 0.0f}));
  objects.push_back(Plane("branch", 5, Bar(0.22f, 0.72f, 0.18f, 0.55f, 0.008f), 0.8f, branch_texture, {0.4f, 0.0f}));
  return {
      {"name", "occluders"},
      {"description", "fine occluders: thin bars and a branch with twigs in front of a checker card and background"},
      {"objects", objects}};
}

json HorseShape(float x, float y, float s) {
  // A crude horse silhouette (body, neck, head, four legs) as one polygon, origin at the body's top-left.
  const float p[][2] = {{0.0f, 0.0f},  {0.45f, 0.0f},  {0.55f, -0.25f}, {0.72f, -0.28f}, {0.7f, -0.15f},
                        {0.6f, 0.0f},  {0.6f, 0.2f},   {0.55f, 0.2f},   {0.55f, 0.45f},  {0.5f, 0.45f},
                        {0.48f, 0.2f}, {0.15f, 0.2f},  {0.12f, 0.45f},  {0.07f, 0.45f},  {0.06f, 0.2f},
                        {0.0f, 0.2f},  {-0.08f, 0.3f}, {-0.1f, 0.25f}};
  json points = json::array();
  for (const auto& q : p) points.push_back({x + q[0] * s, y + q[1] * s});
  return {{"type", "polygon"}, {"points", points}};
}

json TwoHorsesScene() {
  return {{"name", "two-horses"},
          {"description", "two objects of almost the same colour at different depths, one partly behind the other"},
          {"objects",
           {Background(-1.0f, Noise({0.35, 0.55, 0.3}, {0.55, 0.7, 0.45}, 0.1f, 31)),
            Plane("horse-far", 1, HorseShape(0.12f, 0.38f, 0.7f), 0.0f,
                  Noise({0.5, 0.33, 0.2}, {0.58, 0.4, 0.26}, 0.05f, 7)),
            Plane("horse-near", 2, HorseShape(0.38f, 0.5f, 0.7f), 1.1f,
                  Noise({0.52, 0.34, 0.21}, {0.6, 0.41, 0.27}, 0.05f, 8))}}};
}

json SpheresScene() {
  json sphere1 = {{"name", "ball-red"},  {"label", 2},
                  {"type", "ellipsoid"}, {"centre", {0.3, 0.45}},
                  {"radius", 0.17},      {"disparity", 0.2},
                  {"bulge", 0.6},        {"texture", Noise({0.7, 0.15, 0.1}, {0.95, 0.6, 0.4}, 0.04f, 3)}};
  json sphere2 = {{"name", "ball-checker"}, {"label", 3},
                  {"type", "ellipsoid"},    {"centre", {0.68, 0.4}},
                  {"radius", 0.14},         {"disparity", -0.3},
                  {"bulge", 0.4},           {"texture", Checker({0.95, 0.95, 0.95}, {0.1, 0.3, 0.6}, 0.05f)}};
  json sphere3 = {{"name", "ball-small"}, {"label", 4},
                  {"type", "ellipsoid"},  {"centre", {0.52, 0.72}},
                  {"radius", 0.08},       {"disparity", 1.0},
                  {"bulge", 0.3},         {"texture", Stripes({0.2, 0.6, 0.3}, {0.9, 0.9, 0.5}, 0.03f, 60.0f)}};
  return {{"name", "spheres"},
          {"description", "three ellipsoids ('spheres' in disparity space) and a disc in front of a slanted floor"},
          {"objects",
           {Background(-1.3f, Noise({0.6, 0.6, 0.65}, {0.85, 0.85, 0.9}, 0.1f, 41)),
            Plane("floor", 1, Rect(0.0f, 0.55f, 1.0f, 1.0f), -1.0f, Checker({0.8, 0.75, 0.6}, {0.45, 0.4, 0.3}, 0.08f),
                  {0.0f, 3.0f}, {0.5f, 0.55f}),
            sphere1, sphere2, sphere3,
            Plane("disc", 5, {{"type", "disc"}, {"centre", {0.85, 0.78}}, {"radius", 0.1}}, 0.6f,
                  Noise({0.2, 0.2, 0.7}, {0.6, 0.7, 0.95}, 0.03f, 13))}}};
}

json SpecularScene() {
  json glossy = Plane("glossy-card", 1, Rect(0.1f, 0.15f, 0.55f, 0.85f), 0.4f,
                      Noise({0.15, 0.25, 0.5}, {0.3, 0.45, 0.75}, 0.05f, 17));
  glossy["specular"] = {{"centre", {0.3, 0.45}}, {"radius", 0.06}, {"strength", 0.7}, {"shift", 0.03}};
  json glossy2 = Plane("glossy-slant", 2, Rect(0.58f, 0.2f, 0.92f, 0.8f), -0.2f,
                       Checker({0.8, 0.2, 0.2}, {0.95, 0.8, 0.8}, 0.06f), {1.5f, 0.0f}, {0.75f, 0.5f});
  glossy2["specular"] = {{"centre", {0.75, 0.4}}, {"radius", 0.04}, {"strength", 0.8}, {"shift", -0.02}};
  return {{"name", "specular"},
          {"description", "textured planes with view-dependent highlights (non-Lambertian)"},
          {"objects", {Background(-0.8f, Noise({0.4, 0.4, 0.4}, {0.7, 0.7, 0.7}, 0.08f, 51)), glossy, glossy2}}};
}

// One pixel of the 512 x 512 views the hard scenes are laid out for (the HCI benchmark's size; half a pixel at 256).
constexpr float kPixel512 = 1.0f / 512.0f;

json CombScene() {
  // After HCI's backgammon: a comb of thin teeth in front of finely textured surfaces. Four groups of teeth, each
  // tooth w px wide with w px gaps (w = 1..4), then a thin slanted bar that recedes along its length.
  json objects = {Background(-0.9f, Noise({0.3, 0.3, 0.25}, {0.85, 0.8, 0.7}, 0.012f, 61)),
                  Plane("board", 1, Rect(0.0f, 0.55f, 1.0f, 1.0f), -0.5f,
                        Checker({0.85, 0.75, 0.55}, {0.3, 0.2, 0.12}, 0.03f, 10.0f), {0.0f, 1.2f}, {0.5f, 0.55f})};
  const json tooth_texture = Noise({0.45, 0.08, 0.05}, {0.75, 0.2, 0.12}, 0.01f, 62);
  for (int group = 0; group < 4; ++group) {
    const float width = static_cast<float>(group + 1) * kPixel512;
    float x = 0.04f + 0.24f * static_cast<float>(group);
    for (int tooth = 0; tooth < 10; ++tooth, x += 2.0f * width)
      objects.push_back(Plane("comb", 2, Rect(x, 0.06f, x + width, 0.62f), 1.0f, tooth_texture));
  }
  objects.push_back(Plane("slanted-bar", 3, Bar(0.02f, 0.95f, 0.98f, 0.66f, 2.0f * kPixel512), 1.5f,
                          Noise({0.1, 0.2, 0.5}, {0.3, 0.5, 0.9}, 0.01f, 63), {-0.8f, 0.0f}, {0.5f, 0.8f}));
  return {{"name", "comb"},
          {"description",
           "a comb of 1-4 px teeth with 1-4 px gaps and a receding 2 px bar in front of fine texture "
           "(laid out for 512 x 512 views)"},
          {"objects", objects}};
}

json LayersScene() {
  // Several occlusion layers of thin structures: rails behind pickets behind a diagonal branch, a disc in front.
  json objects = {Background(-1.3f, Checker({0.9, 0.9, 0.85}, {0.35, 0.4, 0.45}, 0.016f, 20.0f))};
  const json rail_texture = Noise({0.5, 0.45, 0.3}, {0.7, 0.65, 0.45}, 0.015f, 71);
  for (const float y : {0.3f, 0.5f, 0.7f})
    objects.push_back(Plane("rails", 1, Rect(0.0f, y, 1.0f, y + 3.0f * kPixel512), -0.4f, rail_texture));
  const json picket_texture = Noise({0.8, 0.45, 0.15}, {0.95, 0.65, 0.3}, 0.01f, 72);
  for (float x = 0.05f; x < 0.95f; x += 0.06f)
    objects.push_back(Plane("pickets", 2, Rect(x, 0.15f, x + 2.0f * kPixel512, 0.85f), 0.5f, picket_texture));
  objects.push_back(Plane("branch", 3, Bar(0.1f, 0.1f, 0.9f, 0.9f, 4.0f * kPixel512), 1.3f,
                          Noise({0.25, 0.15, 0.08}, {0.45, 0.3, 0.15}, 0.01f, 73), {0.5f, 0.5f}, {0.5f, 0.5f}));
  objects.push_back(Plane("disc", 4, {{"type", "disc"}, {"centre", {0.75, 0.25}}, {"radius", 0.08}}, 1.9f,
                          Noise({0.1, 0.45, 0.2}, {0.5, 0.85, 0.4}, 0.02f, 74)));
  return {{"name", "layers"},
          {"description",
           "four occlusion layers of thin structures: 3 px rails, 2 px pickets, a 4 px slanted branch "
           "and a disc over a fine checker (laid out for 512 x 512 views)"},
          {"objects", objects}};
}

json BarsScene() {
  // After the benchmark's scenes of many thin bars (issue 43): three backgrounds of different textures at different
  // depths, one above the other, crossed by vertical bars of 1-12 px at three depths in front, and by three
  // horizontal stripes of 2, 5 and 10 px.
  // The walls reach past the frame so that the side views see them too; the background only shows past their ends.
  json objects = {Background(-1.3f, Noise({0.5, 0.5, 0.5}, {0.7, 0.7, 0.7}, 0.02f, 80)),
                  Plane("wall-noise", 1, Rect(-0.05f, -0.05f, 1.05f, 0.34f), -1.0f,
                        Noise({0.3, 0.35, 0.3}, {0.85, 0.8, 0.7}, 0.01f, 81)),
                  Plane("wall-checker", 2, Rect(-0.05f, 0.34f, 1.05f, 0.67f), -0.6f,
                        Checker({0.9, 0.88, 0.8}, {0.3, 0.32, 0.4}, 0.02f, 12.0f)),
                  Plane("wall-stripes", 3, Rect(-0.05f, 0.67f, 1.05f, 1.05f), -0.2f,
                        Stripes({0.7, 0.5, 0.3}, {0.95, 0.85, 0.6}, 0.015f, 70.0f))};
  const float widths[] = {1, 2, 3, 4, 6, 8, 12};
  const float depths[] = {0.4f, 0.9f, 1.5f};
  const json bar_texture = Noise({0.5, 0.1, 0.08}, {0.85, 0.3, 0.2}, 0.008f, 82);
  float x = 0.06f;
  for (int i = 0; i < 7; ++i) {
    const float width = widths[i] * kPixel512;
    objects.push_back(Plane("bar-" + std::to_string(static_cast<int>(widths[i])) + "px", 4 + i,
                            Rect(x, 0.04f, x + width, 0.96f), depths[i % 3], bar_texture));
    x += width + 0.12f;
  }
  const float stripe_widths[] = {2, 5, 10};
  const float stripe_y[] = {0.2f, 0.5f, 0.82f};
  for (int i = 0; i < 3; ++i)
    objects.push_back(Plane("stripe-" + std::to_string(static_cast<int>(stripe_widths[i])) + "px", 11 + i,
                            Rect(0.03f, stripe_y[i], 0.97f, stripe_y[i] + stripe_widths[i] * kPixel512), 1.1f,
                            Noise({0.1, 0.25, 0.5}, {0.35, 0.55, 0.9}, 0.008f, 83 + i)));
  return {{"name", "bars"},
          {"description",
           "vertical bars of 1-12 px at three depths and horizontal stripes of 2-10 px in front of three "
           "differently textured walls (laid out for 512 x 512 views)"},
          {"objects", objects}};
}

json SculptureScene() {
  // After the benchmark's sculpture scenes (issue 43): a smooth, finely textured curved object in front of a
  // textured wall, with a smaller one beside it: smooth surfaces, where sub-pixel precision shows, and their rims.
  const json skin = Noise({0.55, 0.5, 0.45}, {0.8, 0.76, 0.7}, 0.006f, 91);
  json head = {{"name", "sculpture"}, {"label", 1},       {"type", "ellipsoid"}, {"centre", {0.45, 0.48}},
               {"radius", 0.3},       {"disparity", 0.2}, {"bulge", 0.9},        {"texture", skin}};
  json bust = {{"name", "pebble"},    {"label", 2},
               {"type", "ellipsoid"}, {"centre", {0.82, 0.75}},
               {"radius", 0.12},      {"disparity", 0.5},
               {"bulge", 0.4},        {"texture", Noise({0.35, 0.4, 0.45}, {0.7, 0.75, 0.8}, 0.006f, 92)}};
  return {{"name", "sculpture"},
          {"description",
           "a smooth, finely textured ellipsoid and a smaller one in front of a textured wall "
           "(laid out for 512 x 512 views)"},
          {"objects", {Background(-0.8f, Noise({0.4, 0.3, 0.25}, {0.8, 0.65, 0.5}, 0.01f, 93)), head, bust}}};
}

json CheckerboardScene() {
  return {
      {"name", "checkerboard"},
      {"description", "one fronto-parallel black-and-white checkerboard in front of a plain background"},
      {"objects",
       {Background(-0.5f, {{"type", "constant"}, {"colour", {0.5, 0.5, 0.5}}}),
        Plane("board", 1, Rect(0.1f, 0.1f, 0.9f, 0.9f), 0.3f, Checker({0.95, 0.95, 0.95}, {0.05, 0.05, 0.05}, 0.1f))}}};
}

// The real F01 frames' colour bands (issue 49) need what two-horses lacks: large smooth surfaces whose green against
// red and blue sits near the JPEG's quantization threshold at the frames' dark level, in a light bluer than the
// camera's reference. The colours are chosen so that the mosaic's brighter half reads raw R/G 0.87, B/G 0.69 above
// the black level at `--exposure 1.8` (the real IMG_3: 0.84, 0.76; the camera's white balance makes a grey surface
// 1.12, 0.65), and a quarter of the 8x8 blocks keeps the (7,7) coefficient (IMG_3: a third). The third leaf is
// purple, the colour IMG_3's darker leaves decode to.
json LeavesScene() {
  const auto leaf = [](const std::string& name, int label, float cx, float cy, float radius, float disparity,
                       const std::vector<double>& dark, const std::vector<double>& light, int seed) {
    return Plane(name, label, {{"type", "disc"}, {"centre", {cx, cy}}, {"radius", radius}}, disparity,
                 Noise(dark, light, 0.08f, seed));
  };
  return {{"name", "leaves"},
          {"description",
           "large smooth leaves in shade over dark ground: with --exposure 1.8 --mosaic-jpeg 75, the real F01 "
           "frames' JPEG colour bands"},
          {"objects",
           {Background(-0.6f, Noise({0.03, 0.05, 0.062}, {0.10, 0.14, 0.186}, 0.02f, 3)),
            leaf("leaf-bright", 1, 0.35f, 0.4f, 0.28f, 0.2f, {0.20, 0.45, 0.372}, {0.26, 0.55, 0.465}, 5),
            leaf("leaf-dark", 2, 0.72f, 0.62f, 0.22f, 0.6f, {0.12, 0.26, 0.217}, {0.16, 0.32, 0.279}, 7),
            leaf("leaf-purple", 3, 0.3f, 0.82f, 0.2f, -0.2f, {0.22, 0.20, 0.465}, {0.28, 0.26, 0.589}, 9)}}};
}

}  // namespace

std::vector<std::string> BuiltinSceneNames() {
  return {"planes", "occluders", "two-horses", "spheres",   "specular", "checkerboard",
          "comb",   "layers",    "bars",       "sculpture", "leaves"};
}

Scene BuiltinScene(const std::string& name) {
  json json_scene;
  if (name == "planes")
    json_scene = PlanesScene();
  else if (name == "occluders")
    json_scene = OccludersScene();
  else if (name == "two-horses")
    json_scene = TwoHorsesScene();
  else if (name == "spheres")
    json_scene = SpheresScene();
  else if (name == "specular")
    json_scene = SpecularScene();
  else if (name == "checkerboard")
    json_scene = CheckerboardScene();
  else if (name == "comb")
    json_scene = CombScene();
  else if (name == "layers")
    json_scene = LayersScene();
  else if (name == "bars")
    json_scene = BarsScene();
  else if (name == "sculpture")
    json_scene = SculptureScene();
  else if (name == "leaves")
    json_scene = LeavesScene();
  else {
    std::string list;
    for (const auto& n : BuiltinSceneNames()) list += (list.empty() ? "" : ", ") + n;
    throw Error("unknown built-in scene '" + name + "' (expected one of " + list + ")");
  }
  return SceneFromJson(json_scene, ".", "builtin scene " + name);
}

}  // namespace lfsp::simulate
