// `lfsp simulate`: a synthetic scene rendered as an ideal light field or as a Lytro lenslet capture (container,
// white images) with its ground truth. A thin layer over lfsp::simulate::Simulate().

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "command_registry.h"
#include "lfsp/core/error.h"
#include "lfsp/simulate/scene.h"
#include "lfsp/simulate/simulate.h"
#include "stages/summary.h"

namespace lfsp::cli {
namespace {

struct SimulateCommandOptions {
  simulate::SimulateOptions library;
  std::string size = "256x256";
  std::string out;
  std::string storage = "float32";
  bool list_scenes = false;
};

void ParseSize(const std::string& text, int& width, int& height) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1)
    throw Error("--size: expected WxH (e.g. 256x256), got '" + text + "'");
  width = w;
  height = h;
}

void RunSimulate(SimulateCommandOptions& options) {
  if (options.list_scenes) {
    for (const auto& name : simulate::BuiltinSceneNames())
      std::printf("%-13s %s\n", name.c_str(), simulate::BuiltinScene(name).description.c_str());
    return;
  }
  if (options.out.empty()) throw Error("--out: required (the output folder)");
  ParseSize(options.size, options.library.width, options.library.height);
  options.library.ground_truth_storage = options.storage == "uint8"    ? SampleStorage::kUint8
                                         : options.storage == "uint16" ? SampleStorage::kUint16
                                                                       : SampleStorage::kFloat32;
  const simulate::SimulateResult result = simulate::Simulate(options.library, options.out);
  nlohmann::json summary = result.summary;
  summary["out"] = options.out;
  summary["camera_option"] = options.library.camera;
  stages::WriteJsonSummary(summary, stages::SummaryPathFor(options.out));
  for (const auto& file : result.files) std::printf("%s\n", (std::filesystem::path(options.out) / file).c_str());
}

void AddSimulateCommand(CLI::App& app) {
  auto options = std::make_shared<SimulateCommandOptions>();
  simulate::SimulateOptions& lib = options->library;
  CLI::App* command = app.add_subcommand(
      "simulate",
      "Render a synthetic scene as a Lytro lenslet capture (container + white images) or an ideal light field, "
      "with ground truth (disparity, labels, lenslet geometry)");
  command->add_option("--scene", lib.scene, "Built-in scene name (see --list-scenes) or a scene JSON file")
      ->capture_default_str();
  command
      ->add_option("--camera", lib.camera,
                   "Camera model: f01, illum, or mini-illum / mini-f01 (the same optics on a small sensor)")
      ->check(CLI::IsMember({"f01", "illum", "mini-illum", "mini-f01"}))
      ->capture_default_str();
  command->add_option("--seed", lib.seed, "Noise seed; the same seed gives byte-identical files")
      ->capture_default_str();
  command->add_flag("--ideal-only", lib.ideal_only, "Write only the ideal light field (ideal.h5), no lenslet capture");
  command->add_option("--views", lib.views, "Ideal light field: views per axis")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command->add_option("--size", options->size, "Ideal light field: view size WxH")->capture_default_str();
  command->add_option("--supersampling", lib.supersampling, "Ideal light field: anti-aliasing samples per axis")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  command
      ->add_option("--exposure", lib.capture.exposure,
                   "Capture: signal of a white surface at a micro-image centre, as a fraction of white - black")
      ->check(CLI::Range(0.01, 4.0))
      ->capture_default_str();
  command->add_flag("!--no-noise", lib.capture.noise, "Capture: no shot or read noise");
  command->add_option("--hot-pixels", lib.capture.hot_pixels, "Capture: number of stuck-at-white pixels")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command->add_option("--raw-supersampling", lib.capture.supersampling, "Capture: rays per sensor pixel per axis")
      ->check(CLI::Range(1, 8))
      ->capture_default_str();
  command
      ->add_option("--disparity-scale", lib.capture.disparity_scale,
                   "Capture: multiplies the scene disparities (pixels per decoded view step)")
      ->capture_default_str();
  command->add_flag("!--no-white-images", lib.white_images, "Capture: do not write whites/MOD_####.RAW + .TXT");
  command->add_option("--compression", lib.compression_level, "gzip level of the .h5 outputs (0-9)")
      ->check(CLI::Range(0, 9))
      ->capture_default_str();
  command
      ->add_option("--storage", options->storage,
                   "Sample type of the light fields in the .h5 outputs: float32, uint16 or uint8 (smaller, quantised)")
      ->check(CLI::IsMember({"float32", "uint16", "uint8"}))
      ->capture_default_str();
  command
      ->add_option("--calibration", lib.calibration_poses,
                   "Instead of the scene: a checkerboard at this many known poses (calibration/pose_NN/ with "
                   "ground_truth.json); 0 = off")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  command->add_flag("--list-scenes", options->list_scenes, "List the built-in scenes and exit");
  command->add_option("--out", options->out, "Output folder (created if needed)");
  command->callback([options] { RunSimulate(*options); });
}

}  // namespace

LFSP_REGISTER_COMMAND(20, "simulate", AddSimulateCommand);

}  // namespace lfsp::cli
