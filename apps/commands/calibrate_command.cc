// `lfsp calibrate CAPTURE... --out cal.json`: checkerboard calibration of a lenslet camera from decoded captures
// (Dansereau, Pizarro and Williams 2013; see calibrate/include/lfsp/calibrate/calibration.h).

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/calibrate/calibration.h"
#include "lfsp/calibrate/calibration_io.h"
#include "lfsp/calibrate/corners.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/stopwatch.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct CalibrateCommandOptions {
  std::vector<std::string> captures;
  std::string out;
  std::string corners = "19x19";
  double square_size_mm = 3.61;
  double min_view_weight = 0.2;
  int view_border = -1;
  int min_captures = 3;
  int max_iterations = 100;
  bool allow_mixed_settings = false;
};

// "19x19" -> 19, 19; "auto" -> 0, 0 (partial-board mode, see CornerDetectionOptions).
void ParseCorners(const std::string& text, int& x, int& y) {
  if (text == "auto") {
    x = y = 0;
    return;
  }
  char separator = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &x, &separator, &y, &extra) != 3 ||
      (separator != 'x' && separator != 'X') || x < 3 || y < 3 || x > 200 || y > 200) {
    throw Error("--corners '" + text + "': expected inner corners as WxH, e.g. 19x19 (each 3..200), or auto");
  }
}

void RunCalibrate(const CalibrateCommandOptions& options) {
  const Stopwatch stopwatch;
  calibrate::CornerDetectionOptions detection;
  ParseCorners(options.corners, detection.corners_x, detection.corners_y);
  detection.min_view_weight = options.min_view_weight;
  detection.view_border = options.view_border;
  if (!(options.square_size_mm > 0)) throw Error("--square-size must be positive (millimetres)");

  // One capture in memory at a time: only its corners are kept.
  std::vector<calibrate::CaptureCorners> corners;
  std::vector<std::string> not_found;
  Progress progress("corners", options.captures.size());  // drawn only on a terminal
  for (const auto& path : options.captures) {
    progress.Tick(0);
    const Bundle bundle = LoadInput(path);
    try {
      corners.push_back(calibrate::DetectCaptureCorners(bundle.light_field, path, detection));
      const auto& c = corners.back();
      spdlog::info("{}: board tracked in {} views ({} dark, {} at the lenslet's edge, {} failed)", path, c.views.size(),
                   c.dark_views.size(), c.edge_views.size(), c.failed_views.size());
    } catch (const Error& e) {
      spdlog::warn("{}", e.what());
      not_found.push_back(e.what());
    }
    progress.Tick();
  }
  progress.Finish();
  if (corners.empty()) {
    throw Error("no " + options.corners + " checkerboard found in any of the " +
                std::to_string(options.captures.size()) +
                " captures (check --corners: it counts inner corners, one less than the squares per side)");
  }

  calibrate::CalibrationOptions calibration_options;
  calibration_options.square_size = options.square_size_mm * 1e-3;
  calibration_options.min_captures = options.min_captures;
  calibration_options.max_iterations = options.max_iterations;
  calibration_options.allow_mixed_settings = options.allow_mixed_settings;
  if (static_cast<int>(corners.size()) < options.min_captures) {
    std::string names;
    for (const auto& n : not_found) names += "; " + n;
    throw Error("only " + std::to_string(corners.size()) + " of " + std::to_string(options.captures.size()) +
                " captures show the board, need at least " + std::to_string(options.min_captures) + names);
  }
  calibrate::Calibration result = calibrate::Calibrate(corners, calibration_options);
  for (const auto& n : not_found) {
    result.rejected_captures.push_back(n);
    result.warnings.push_back("dropped " + n);
  }
  calibrate::WriteCalibration(result, options.out);

  const double seconds = stopwatch.Seconds();
  std::printf("RMS ray reprojection error %.4f mm over %zu captures (%s)\n", result.rms_mm, result.captures.size(),
              options.out.c_str());
  nlohmann::json summary = {{"command", "calibrate"},
                            {"inputs", options.captures},
                            {"output", options.out},
                            {"parameters",
                             {{"corners", options.corners},
                              {"square_size_mm", options.square_size_mm},
                              {"min_view_weight", options.min_view_weight},
                              {"view_border", options.view_border},
                              {"min_captures", options.min_captures},
                              {"max_iterations", options.max_iterations},
                              {"allow_mixed_settings", options.allow_mixed_settings}}},
                            {"rms_mm", result.rms_mm},
                            {"captures_used", result.captures.size()},
                            {"rejected_captures", result.rejected_captures},
                            {"warnings", result.warnings},
                            {"seconds", seconds}};
  stages::WriteJsonSummary(summary, stages::SummaryPathFor(options.out));
}

void AddCalibrateCommand(CLI::App& app) {
  auto options = std::make_shared<CalibrateCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "calibrate",
      "Calibrate a lenslet camera from decoded checkerboard captures (one light field per board pose, same zoom and "
      "focus): 4D intrinsic matrix, distortion and poses, as JSON");
  command->add_option("captures", options->captures, "Decoded checkerboard light fields (.h5 bundles or views folders)")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--out", options->out, "Output calibration JSON")->required();
  command
      ->add_option("--corners", options->corners,
                   "Inner corners of the board, WxH; or auto: whatever part of the board each capture shows, for "
                   "boards larger than the views (corners within one square of a view's edge are left out)")
      ->capture_default_str();
  command->add_option("--square-size", options->square_size_mm, "Checker square side in millimetres")
      ->capture_default_str();
  command
      ->add_option("--min-view-weight", options->min_view_weight,
                   "Skip views whose mean weight (vignetting) is below this")
      ->capture_default_str();
  command
      ->add_option("--view-border", options->view_border,
                   "Also skip views within N view steps of the lenslet's edge (a dark view or the edge of the view "
                   "grid), whose rays the linear camera model fits worst; -1 = automatic: 1 (as LFToolbox) on light "
                   "fields decoded from a lenslet capture, 0 on others")
      ->capture_default_str()
      ->check(CLI::Range(-1, 16));
  command->add_option("--min-captures", options->min_captures, "Fail with fewer usable captures than this")
      ->capture_default_str();
  command->add_option("--max-iterations", options->max_iterations, "Solver iterations per stage")
      ->capture_default_str();
  command->add_flag("--allow-mixed-settings", options->allow_mixed_settings,
                    "Warn instead of failing when captures differ in camera, zoom step or focus step (default: off)");
  command->callback([options] { RunCalibrate(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(50, "calibrate", AddCalibrateCommand);

}  // namespace lfsp::cli
