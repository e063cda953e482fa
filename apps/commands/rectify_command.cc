// `lfsp rectify LF --calibration cal.json --out OUT`: resample a decoded light field so it follows an ideal,
// undistorted intrinsic matrix (recorded in the output's metadata as calibration.H).

#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "command_registry.h"
#include "input_loading.h"
#include "lfsp/calibrate/calibration_io.h"
#include "lfsp/calibrate/rectify.h"
#include "lfsp/core/error.h"
#include "lfsp/core/load.h"
#include "lfsp/core/stopwatch.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct RectifyCommandOptions {
  std::string input;
  std::string calibration;
  std::string out;
  int inverse_iterations = 8;
  int bit_depth = 16;
};

void RunRectify(const RectifyCommandOptions& options) {
  const Stopwatch stopwatch;
  if (options.bit_depth != 8 && options.bit_depth != 16) throw Error("--bit-depth must be 8 or 16");
  if (options.inverse_iterations < 0 || options.inverse_iterations > 100)
    throw Error("--inverse-iterations must be in 0..100");
  const calibrate::Calibration calibration = calibrate::ReadCalibration(options.calibration);
  Bundle bundle = LoadInput(options.input);
  const LightFieldShape& shape = bundle.light_field.shape();
  const LightFieldShape& expected = calibration.shape;
  if (shape.nu != expected.nu || shape.nv != expected.nv || shape.width != expected.width ||
      shape.height != expected.height) {
    throw Error(options.input + ": light field " + ToString(shape) + " does not match the calibration " +
                options.calibration + " (" + std::to_string(expected.nu) + "x" + std::to_string(expected.nv) +
                " views of " + std::to_string(expected.width) + "x" + std::to_string(expected.height) + ")");
  }
  const auto& metadata = bundle.light_field.metadata;
  if (metadata.is_object() && metadata.contains("calibration") && metadata["calibration"].is_object() &&
      metadata["calibration"].value("rectified", false)) {
    throw Error(options.input + ": this light field is already rectified (metadata calibration.rectified)");
  }

  const calibrate::RayModel rectified = calibrate::RectifiedModel(calibration.model, shape);
  calibrate::RectifyOptions rectify_options;
  rectify_options.inverse_distortion_iterations = options.inverse_iterations;
  Bundle out;
  out.light_field = calibrate::Rectify(bundle.light_field, calibration.model, rectified, rectify_options);
  if (bundle.disparity || bundle.labels)
    spdlog::warn("{}: the disparity map and labels are not carried over (they belong to the unrectified views)",
                 options.input);
  out.light_field.metadata["calibration"] = {{"rectified", true},
                                             {"H", calibrate::MatrixToJson(rectified.H)},
                                             {"distortion", {0.0, 0.0, 0.0, 0.0, 0.0}},
                                             {"calibrated_H", calibrate::MatrixToJson(calibration.model.H)},
                                             {"calibration_file", options.calibration}};
  SaveLightField(out, options.out, options.bit_depth);

  const double seconds = stopwatch.Seconds();
  nlohmann::json summary = {
      {"command", "rectify"},
      {"input", options.input},
      {"calibration", options.calibration},
      {"output", options.out},
      {"parameters", {{"inverse_iterations", options.inverse_iterations}, {"bit_depth", options.bit_depth}}},
      {"rectified_H", calibrate::MatrixToJson(rectified.H)},
      {"seconds", seconds}};
  stages::WriteJsonSummary(summary, stages::SummaryPathFor(options.out));
}

void AddRectifyCommand(CLI::App& app) {
  auto options = std::make_shared<RectifyCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "rectify",
      "Resample a decoded light field through a calibration so it follows an ideal undistorted intrinsic matrix "
      "(square pixels, views related by pure disparity shifts), recorded in the output's metadata");
  command->add_option("light_field", options->input, "Decoded light field (.h5 bundle or views folder)")
      ->required()
      ->check(CLI::ExistingPath);
  command
      ->add_option("--calibration", options->calibration,
                   "Calibration JSON from `lfsp calibrate`, or LFToolbox's CalInfo.json")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "Output: a .h5 bundle, or a views folder")->required();
  command
      ->add_option("--inverse-iterations", options->inverse_iterations,
                   "Fixed-point iterations of the inverse distortion")
      ->capture_default_str();
  command->add_option("--bit-depth", options->bit_depth, "Bits per sample of PNG views (8 or 16; .h5 keeps floats)")
      ->capture_default_str();
  command->callback([options] { RunRectify(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(60, "rectify", AddRectifyCommand);

}  // namespace lfsp::cli
