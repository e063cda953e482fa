#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/decode/raw_input.h"
#include "lfsp/depth/depth_estimator.h"
#include "lfsp/segment/params.h"

namespace lfsp::pipeline {

// `lfsp pipeline`: raw capture (with white images) or light field -> decode -> depth -> segment -> optional
// recolour -> report. Every intermediate is written into `out` in the project's formats.
struct PipelineOptions {
  std::filesystem::path input;         // empty: the bundled sample
  std::filesystem::path out;           // output folder (created; replaced only if it holds a previous run)
  std::filesystem::path white_images;  // for raw captures; empty: beside the capture
  bool no_white_image = false;         // estimate the white image and grid from the capture (CaptureDecodeOptions)
  std::filesystem::path grid;          // a lenslet grid to use instead of fitting one (CaptureDecodeOptions)
  decode::PlainRawOptions plain;       // a plain raw image (PNG/TIFF/JPEG Bayer mosaic) is the input when camera is set
  depth::DepthOptions depth;
  segment::LfspParams segment;
  std::string recolor;  // "" = none; see RecolorSpec in recolor_spec.h
  int focal_stack_slices = 5;
  int views = 0;  // central N x N views to process; 0 = the well-lit ones (ChooseViews)
};

// What the run produced, for the report and the summary.
struct PipelineResult {
  nlohmann::ordered_json summary;  // inputs, parameters, outputs, metrics, stage timings, wall time
  std::filesystem::path report;    // report.html
};

PipelineResult RunPipeline(const PipelineOptions& options);

// The bundled default input: the installed samples (<prefix>/share/lfsp/samples), else samples/ of the source tree
// (LFSP_SAMPLES_DIR overrides).
std::filesystem::path DefaultSample();

}  // namespace lfsp::pipeline
