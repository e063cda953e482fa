#include "lfsp/simulate/calibration_set.h"

#include <cmath>

#include "lfsp/core/error.h"

namespace lfsp::simulate {

PinholeRig CalibrationRig() {
  PinholeRig rig;
  rig.focal = 1.2f;
  rig.disparity_gain = 0.6f;
  rig.focus_distance = 0.5f;
  return rig;
}

std::vector<Board> CalibrationBoards(int count) {
  if (count < 1 || count > 100) throw Error("calibration: pose count must be 1..100");
  std::vector<Board> boards;
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < count; ++k) {
    Board board;
    board.rows = 6;
    board.cols = 8;
    board.square = 0.025f;
    const double phase = 2.0 * kPi * k / count;
    const double tilt = (k == 0 ? 0.0 : 0.35);  // the first pose is fronto-parallel
    board.rotation = {static_cast<float>(tilt * std::sin(phase)), static_cast<float>(tilt * std::cos(phase)),
                      static_cast<float>(0.1 * std::sin(3.0 * phase))};
    const float z = static_cast<float>(0.38 + 0.27 * (0.5 + 0.5 * std::sin(1.7 * k + 0.3)));
    // Place the board centre near the optical axis: T = centre - R (w/2, h/2, 0).
    board.translation = {0.0f, 0.0f, 0.0f};
    const auto mid = BoardToCamera(board, 0.5f * board.cols * board.square, 0.5f * board.rows * board.square);
    const float cx = static_cast<float>(0.02 * std::cos(2.3 * k)), cy = static_cast<float>(0.015 * std::sin(1.3 * k));
    board.translation = {cx - mid[0], cy - mid[1], z - mid[2]};
    boards.push_back(board);
  }
  return boards;
}

Scene CalibrationScene(const Board& board, const PinholeRig& rig) {
  Scene scene;
  scene.name = "calibration-board";
  scene.description = "a checkerboard at a known pose in front of a grey background";
  scene.rig = rig;
  SceneObject background;
  background.name = "background";
  background.label = 0;
  background.disparity = rig.Disparity(1.5f);
  background.texture.colour_a = background.texture.colour_b = {0.45f, 0.45f, 0.45f};
  scene.objects.push_back(background);
  SceneObject object;
  object.name = "board";
  object.label = 1;
  object.geometry = SceneObject::Geometry::kBoard;
  object.board = board;
  scene.objects.push_back(object);
  return scene;
}

nlohmann::json CalibrationGroundTruth(const Scene& scene, int width, int height) {
  const SceneObject* board_object = nullptr;
  for (const auto& object : scene.objects)
    if (object.geometry == SceneObject::Geometry::kBoard) board_object = &object;
  if (board_object == nullptr) throw Error("calibration: scene '" + scene.name + "' has no board");
  const Board& board = board_object->board;
  const PinholeRig& rig = scene.rig;
  const double f = rig.focal * width, cx = 0.5 * (width - 1), cy = 0.5 * (height - 1);
  nlohmann::json corners = nlohmann::json::array();
  int index = 0;
  for (int l = 1; l < board.rows; ++l)
    for (int k = 1; k < board.cols; ++k, ++index) {
      const float bx = static_cast<float>(k) * board.square, by = static_cast<float>(l) * board.square;
      const auto p = BoardToCamera(board, bx, by);
      corners.push_back({{"index", index},
                         {"board_m", {bx, by}},
                         {"camera_m", {p[0], p[1], p[2]}},
                         {"centre_px", {f * p[0] / p[2] + cx, f * p[1] / p[2] + cy}},
                         {"disparity", rig.Disparity(p[2])}});
    }
  return {{"frame", {{"width", width}, {"height", height}}},
          {"intrinsics",
           {{"focal_px", f},
            {"cx_px", cx},
            {"cy_px", cy},
            {"disparity_gain_px_m", rig.disparity_gain},
            {"focus_distance_m", rig.focus_distance},
            {"baseline_m_per_view", rig.disparity_gain / f},
            {"model",
             "view (s, t) = (u-uc, v-vc) is a pinhole at (s B, t B, 0) looking along +Z with focal focal_px and "
             "principal point (cx, cy), sheared so that Z = focus_distance has zero disparity: a camera point (X, Y, "
             "Z) appears in view (s, t) at (f X/Z + cx - s d, f Y/Z + cy - t d) with d = fB (1/Z - 1/Z0)"}}},
          {"board",
           {{"rows", board.rows},
            {"cols", board.cols},
            {"square_m", board.square},
            {"rotation_rodrigues", board.rotation},
            {"translation_m", board.translation},
            {"pose", "camera point = R(rotation) * (bx, by, 0) + translation"}}},
          {"corners", corners}};
}

}  // namespace lfsp::simulate
