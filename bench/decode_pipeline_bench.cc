// Decode stage, decoding half (issue 4): the lenslet grid model of a full-size Illum white image (target <= 3 s)
// and decoding a full-size Illum capture 7728x5368 -> 15x15x434x625 (target <= 2 s wall on 2 cores, <= 3 GB).
// Inputs come from the simulator (its Illum preset, built from real metadata), so quality is measured against
// its ground truth: the exact lattice, and the ideal light field on the decoded grid.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "bench_case.h"
#include "lfsp/decode/lenslet_decoder.h"
#include "lfsp/decode/lenslet_grid.h"
#include "lfsp/simulate/lytro_writer.h"
#include "lfsp/simulate/raw_capture.h"
#include "lfsp/simulate/scene.h"

namespace lfsp::bench {
namespace {

struct IllumShot {
  simulate::CameraModel camera;
  decode::RawImage capture;
  decode::RawImage white;
  simulate::LensletLattice truth;
  decode::LytroMetadata capture_metadata;
  decode::LytroMetadata white_metadata;
  std::optional<decode::LensletGrid> grid;
  std::optional<decode::PreparedWhite> prepared;
  LightField truth_inner;  // the ideal light field's inner 9x9 views (PSNR), the rest dropped to save memory
  int inner_offset = 0;
};

IllumShot& Shot() {
  static IllumShot shot;  // each case runs in its own process
  return shot;
}

decode::RawImage ToRaw(const simulate::RawCapture& capture) {
  decode::RawImage raw;
  raw.width = capture.width;
  raw.height = capture.height;
  raw.pixels = capture.pixels;
  return raw;
}

void PrepareWhite() {
  IllumShot& shot = Shot();
  shot.camera = simulate::CameraPreset("illum");
  const simulate::RawCapture white = simulate::RenderWhiteImage(shot.camera, shot.camera.capture_setting, 5);
  shot.truth = white.lattice;
  shot.white_metadata =
      decode::ParseMetadataDocument(simulate::WhiteImageMetadata(shot.camera, white).dump(), "MOD_0003.TXT");
  shot.white = ToRaw(white);
}

decode::LensletGrid EstimateGrid() {
  IllumShot& shot = Shot();
  const cv::Mat grey = decode::WhiteImageToGrey(shot.white, shot.white_metadata.RequireRawFormat(), "white");
  return decode::EstimateLensletGrid(
             grey, decode::GuessFromMetadata(shot.white_metadata, shot.white.width, shot.white.height))
      .grid;
}

void PrepareCapture() {
  PrepareWhite();
  IllumShot& shot = Shot();
  const simulate::Scene scene = simulate::BuiltinScene("planes");
  simulate::CaptureOptions options;
  options.noise = false;
  options.supersampling = 2;  // as the decode test: sensor pixels integrate over their area
  const simulate::RawCapture capture = simulate::RenderRawCapture(scene, shot.camera, options);
  shot.capture_metadata = decode::ParseFrameMetadata(simulate::FrameMetadata(shot.camera, capture),
                                                     simulate::PrivateMetadata(shot.camera), "capture");
  shot.capture = ToRaw(capture);
  shot.grid = EstimateGrid();
  // White images are processed once (grid model, devignetting map), like LFToolbox's white-image database.
  decode::DecodeOptions decode_options;
  decode_options.colour = decode::ColourMode::kLinear;
  shot.prepared = decode::PrepareWhite(shot.white, shot.white_metadata, decode_options.colour);
  // Keep the inner 9x9 views of the ideal light field only.
  const LightField truth = simulate::RenderDecodedGroundTruth(scene, shot.camera, options, 2).light_field;
  const LightFieldShape& full = truth.shape();
  LightFieldShape inner = full;
  inner.nu = inner.nv = 9;
  shot.inner_offset = (full.nu - 9) / 2;
  shot.truth_inner = LightField(inner);
  for (int v = 0; v < 9; ++v)
    for (int u = 0; u < 9; ++u) {
      const float* from = truth.ViewData({u + shot.inner_offset, v + shot.inner_offset});
      std::copy(from, from + full.ViewSamples(), shot.truth_inner.ViewData({u, v}));
    }
}

// Peak resident memory since the last reset (Linux: /proc/self/clear_refs "5" resets VmHWM).
void ResetPeakMemory() { std::ofstream("/proc/self/clear_refs") << "5"; }
double PeakMemoryMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

// PSNR of the decoded inner 9x9 views against the ideal light field after the best global gain (exposure is a free
// scale), away from a 2-pixel border.
double InnerPsnr(const LightField& decoded) {
  const IllumShot& shot = Shot();
  const LightFieldShape& shape = shot.truth_inner.shape();
  double dot = 0.0, norm = 0.0, truth_energy = 0.0;
#pragma omp parallel for collapse(2) reduction(+ : dot, norm, truth_energy)
  for (int v = 0; v < 9; ++v)
    for (int u = 0; u < 9; ++u)
      for (int y = 2; y < shape.height - 2; ++y)
        for (int x = 2; x < shape.width - 2; ++x)
          for (int c = 0; c < 3; ++c) {
            const double d = decoded.at({u + shot.inner_offset, v + shot.inner_offset}, y, x, c);
            const double t = shot.truth_inner.at({u, v}, y, x, c);
            dot += d * t;
            norm += d * d;
            truth_energy += t * t;
          }
  const double gain = dot / norm;
  const double squared = truth_energy - 2.0 * gain * dot + gain * gain * norm;
  const double count = 81.0 * (shape.height - 4) * (shape.width - 4) * 3.0;
  return 10.0 * std::log10(count / squared);
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "grid-model-illum";
  c.input = "Illum white image 7728x5368 (simulated)";
  c.target = "<= 3 s";
  c.repetitions = 3;
  c.prepare = PrepareWhite;
  c.run = [] {
    const decode::LensletGrid grid = EstimateGrid();
    const simulate::LensletLattice& truth = Shot().truth;
    char text[160];
    std::snprintf(text, sizeof text, "centres rms %.4f px, rot err %.1e rad, spacing err %.1e",
                  decode::CentreRmsFrom(grid, truth), std::abs(grid.rotation - truth.rotation),
                  std::abs(grid.spacing_x / truth.spacing - 1.0));
    return std::string(text);
  };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "decode-illum";
  c.input = "Illum 7728x5368 -> 15x15x434x625";
  c.target = "<= 2 s, <= 3 GB";
  c.repetitions = 3;
  c.prepare = PrepareCapture;
  c.run = [] {
    IllumShot& shot = Shot();
    ResetPeakMemory();
    const double before = PeakMemoryMb();
    decode::DecodeOptions options;
    options.colour = decode::ColourMode::kLinear;
    decode::DecodeReport report;
    const LightField decoded =
        decode::DecodeLenslet(shot.capture, shot.capture_metadata, *shot.prepared, *shot.grid, options, &report);
    const double decode_peak = PeakMemoryMb() - before;
    double cpu = 0.0;
    for (const auto& [step, seconds] : report.cpu_seconds) cpu += seconds;
    char text[200];
    std::snprintf(text, sizeof text, "%dx%dx%dx%d, inner 9x9 PSNR %.2f dB, cpu %.2f s, decode +%.0f MB",
                  decoded.shape().nu, decoded.shape().nv, decoded.shape().height, decoded.shape().width,
                  InnerPsnr(decoded), cpu, decode_peak);
    return std::string(text);
  };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "white-prepare-illum";
  c.input = "Illum white image 7728x5368 (simulated)";
  c.target = "- (once per white image)";
  c.repetitions = 3;
  c.prepare = PrepareWhite;
  c.run = [] {
    const decode::PreparedWhite prepared =
        decode::PrepareWhite(Shot().white, Shot().white_metadata, decode::ColourMode::kCamera);
    return "devignetting map + grey " + std::to_string(prepared.inverse.cols) + "x" +
           std::to_string(prepared.inverse.rows);
  };
  return c;
}

// Issue 13: the lattice from the capture itself (no white image), and a decode without one.
LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "grid-capture-illum";
  c.input = "Illum capture 7728x5368, planes scene (simulated)";
  c.target = "<= 1 s";
  c.repetitions = 3;
  c.baseline = "grid-model-illum";
  c.prepare = PrepareCapture;
  c.run = [] {
    IllumShot& shot = Shot();
    const decode::LensletGrid grid = decode::FindLensletGridInCapture(shot.capture, shot.capture_metadata).grid;
    char text[160];
    std::snprintf(text, sizeof text, "%d x %d lenses, centres rms vs truth %.4f px", grid.columns, grid.rows,
                  decode::CentreRmsFrom(grid, shot.truth));
    return std::string(text);
  };
  return c;
}

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "decode";
  c.name = "decode-no-white-illum";
  c.input = "Illum 7728x5368, no white image -> 15x15x434x625";
  c.target = "PSNR within 1 dB of decode-illum";
  c.repetitions = 3;
  c.baseline = "decode-illum";
  c.prepare = PrepareCapture;
  c.run = [] {
    IllumShot& shot = Shot();
    decode::DecodeOptions options;
    options.colour = decode::ColourMode::kLinear;
    const decode::LensletGrid grid = decode::FindLensletGridInCapture(shot.capture, shot.capture_metadata).grid;
    const decode::RawImage white = decode::EstimateWhiteImageFromCapture(shot.capture, shot.capture_metadata, grid);
    const decode::PreparedWhite prepared = decode::PrepareWhite(white, shot.capture_metadata, options.colour);
    const LightField decoded = decode::DecodeLenslet(shot.capture, shot.capture_metadata, prepared, grid, options);
    char text[160];
    std::snprintf(text, sizeof text, "grid + white estimate + decode, inner 9x9 PSNR %.2f dB", InnerPsnr(decoded));
    return std::string(text);
  };
  return c;
}

}  // namespace lfsp::bench
