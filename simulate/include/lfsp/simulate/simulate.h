#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/simulate/raw_capture.h"

namespace lfsp::simulate {

// What `lfsp simulate` does, as a library call.
struct SimulateOptions {
  std::string scene = "planes";       // built-in name or JSON file
  std::string camera = "mini-illum";  // f01 | illum | mini-illum
  std::uint64_t seed = 1;
  bool ideal_only = false;  // only the ideal light field (no lenslet capture)
  int views = 9;            // ideal light field: views per axis
  int width = 256;          // ideal light field: view size
  int height = 256;
  int supersampling = 3;               // ideal light field anti-aliasing (per axis)
  CaptureOptions capture;              // lenslet capture (seed is taken from `seed`)
  int ground_truth_supersampling = 2;  // decoded ground truth anti-aliasing (per axis)
  bool white_images = true;            // write whites/MOD_####.RAW + .TXT for every lens setting
  SampleStorage ground_truth_storage = SampleStorage::kFloat32;
  int compression_level = 0;    // gzip level of the .h5 files (0-9)
  int calibration_poses = 0;    // > 0: instead of the scene, a checkerboard at this many known poses
  int mosaic_jpeg_quality = 0;  // > 0: also the capture's mosaic as an 8-bit greyscale JPEG (WriteMosaicJpeg)
};

struct SimulateResult {
  nlohmann::json summary;                    // inputs, parameters, files, timings
  std::vector<std::filesystem::path> files;  // everything written, relative to the output folder
};

// Writes into `out_dir` (created if needed), every file atomically:
//   ideal-only: ideal.h5 (LF, centre disparity, labels), scene.json
//   otherwise:  capture.LFR (Illum) / capture.lfp (F01); whites/MOD_####.RAW + .TXT; scene.json;
//               with mosaic_jpeg_quality, capture_mosaic.jpg (the same mosaic as a real F01 frame export) and
//               capture_mosaic.png (the same 8 bits, lossless);
//               ground_truth/decoded.h5 (ideal LF on the decoded grid, linear, weights, disparity, labels) and
//               ground_truth/lenslet_geometry.json.
//   calibration_poses > 0: calibration/pose_NN/ holds each checkerboard capture (or ideal.h5 with --ideal-only) and
//               its ground_truth.json (intrinsics, pose, corners; see CalibrationGroundTruth), instead of the scene.
// Same options and seed -> byte-identical files (except HDF5 object timestamps inside the .h5 files).
SimulateResult Simulate(const SimulateOptions& options, const std::filesystem::path& out_dir);

}  // namespace lfsp::simulate
