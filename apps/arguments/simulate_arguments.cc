#include "arguments/simulate_arguments.h"

#include <cstdio>

#include "lfsp/core/error.h"

namespace lfsp::cli {
namespace {

void ParseSize(const std::string& text, int& width, int& height) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || (x != 'x' && x != 'X') || w < 1 || h < 1)
    throw Error(OptionName("size") + ": expected WxH (e.g. 256x256), got '" + text + "'");
  width = w;
  height = h;
}

}  // namespace

void AddSimulateArguments(CLI::App* command, SimulateArguments& arguments) {
  simulate::SimulateOptions& lib = arguments.library;
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
  command->add_option("--size", arguments.size, "Ideal light field: view size WxH")->capture_default_str();
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
      ->add_option("--lens-samples", lib.capture.lens_samples,
                   "Capture: rays per axis across each micro-lens's aperture (1 = through its centre only; 0 = "
                   "automatic: 3 for --calibration, else 1)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  command
      ->add_option("--disparity-scale", lib.capture.disparity_scale,
                   "Capture: multiplies the scene disparities (pixels per decoded view step)")
      ->capture_default_str();
  command->add_flag("!--no-white-images", lib.white_images, "Capture: do not write whites/MOD_####.RAW + .TXT");
  command
      ->add_option(
          "--mosaic-jpeg", lib.mosaic_jpeg_quality,
          "Capture: also write capture_mosaic.jpg, the mosaic as real F01 frames were exported (raw codes "
          "scaled to 8 bits, greyscale JPEG at this quality; those frames: 75), and capture_mosaic.png, the same 8 "
          "bits lossless; 0 = off")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  command->add_option("--compression", lib.compression_level, "gzip level of the .h5 outputs (0-9)")
      ->check(CLI::Range(0, 9))
      ->capture_default_str();
  command
      ->add_option("--storage", arguments.storage,
                   "Sample type of the light fields in the .h5 outputs: float32, uint16 or uint8 (smaller, quantised)")
      ->check(CLI::IsMember({"float32", "uint16", "uint8"}))
      ->capture_default_str();
  command
      ->add_option("--calibration", lib.calibration_poses,
                   "Instead of the scene: a checkerboard at this many known poses (calibration/pose_NN/ with "
                   "ground_truth.json); 0 = off")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
}

simulate::SimulateOptions ToSimulateOptions(const SimulateArguments& arguments) {
  simulate::SimulateOptions options = arguments.library;
  ParseSize(arguments.size, options.width, options.height);
  options.ground_truth_storage = arguments.storage == "uint8"    ? SampleStorage::kUint8
                                 : arguments.storage == "uint16" ? SampleStorage::kUint16
                                                                 : SampleStorage::kFloat32;
  return options;
}

}  // namespace lfsp::cli
