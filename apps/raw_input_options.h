#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "lfsp/decode/raw_input.h"

namespace lfsp::cli {

// The options that say how to read a plain raw image (a Bayer mosaic in a PNG/TIFF/JPEG without Lytro metadata),
// shared by info, grid, decode and pipeline.
struct PlainRawArguments {
  std::string camera;
  std::string bayer;
  double black = -1.0;
  double white = -1.0;
  int jpeg_restore = decode::PlainRawOptions{}.jpeg_restore_iterations;
  std::string jpeg_grey{decode::ToString(decode::PlainRawOptions{}.jpeg_grey)};
};

void AddPlainRawOptions(CLI::App* command, PlainRawArguments& arguments);

// lfsp::Error for an unknown Bayer pattern or camera.
decode::PlainRawOptions ToPlainRawOptions(const PlainRawArguments& arguments);

}  // namespace lfsp::cli
