#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lfsp::noise_study {

// `lfsp noise-study`: how segmentation quality degrades with noise, for LFSP and the per-view baselines, on a
// simulated scene with ground truth. Two kinds of noise:
//   image noise  Gaussian noise of standard deviation sigma added to the ideal light field;
//   low light    the lenslet capture rendered at a lower exposure (fewer photons: shot noise and read noise grow),
//                decoded in scene-linear colour, brought back to the reference brightness by a gain (as a camera's
//                ISO would), then sRGB-encoded like a camera-colour decode; the central `capture_views` views are
//                kept.
// At every level, depth is estimated from the noisy light field (LFSP runs on that disparity), then LFSP, per-view
// SLIC and per-view LSC segment it, and every metric of `lfsp evaluate segmentation` is computed against the
// ground truth.
struct NoiseStudyOptions {
  std::string scene = "planes";  // built-in scene name or scene JSON file
  int views = 9;                 // ideal light field: views per axis
  int width = 256;               // ideal light field: view size
  int height = 256;
  std::vector<double> sigmas = {0.0, 0.01, 0.02, 0.04, 0.08};  // image-noise levels (samples in [0, 1])
  std::string camera = "illum";                                // low-light captures (full-size sensor by default)
  std::vector<double> exposures = {0.7, 0.2, 0.06, 0.02};      // fractions of the white level (see simulate)
  int capture_views = 9;  // central views kept of each decoded capture (the outer ones are vignetted); 0 = all
  int size = 20;          // superpixel size on the ideal light field
  int capture_size = 20;  // superpixel size on the decoded captures
  bool lsc = true;        // include per-view LSC (the slowest baseline)
  std::uint64_t seed = 1;
  std::filesystem::path out;
};

struct NoiseStudyResult {
  nlohmann::ordered_json summary;
  std::vector<std::filesystem::path> plots;
};

NoiseStudyResult RunNoiseStudy(const NoiseStudyOptions& options);

}  // namespace lfsp::noise_study
