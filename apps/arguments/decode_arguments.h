#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "lfsp/decode/capture_decoder.h"
#include "raw_input_options.h"

namespace lfsp::cli {

// The options of `lfsp decode` that say how to decode (not where to write), as the command line and the Python
// module spell them.
struct DecodeArguments {
  std::string white_images;
  bool no_white_image = false;
  std::string grid;
  std::string demosaic = "gradient";
  std::string colour = "camera";
  std::string white_balance;  // "" = the default: camera for Lytro files, auto for plain raw images
  bool no_hot_pixels = false;
  double dehex = 0.1;
  bool no_lattice_flattening = false;
  bool no_jpeg_block_flattening = false;
  int views = -1;  // DecodeOptions::central_views
  PlainRawArguments plain;
};

void AddDecodeArguments(CLI::App* command, DecodeArguments& arguments);

// --grid FILE, for every command that decodes raw captures (decode, pipeline).
void AddGridFileOption(CLI::App* command, std::string& grid_file);

// The decoder's options; lfsp::Error for an unknown demosaic, colour mode, camera or Bayer pattern, or a dehex
// strength outside [0, 0.25].
decode::CaptureDecodeOptions ToCaptureDecodeOptions(const DecodeArguments& arguments);

// The parameters as given, for the summary.
nlohmann::json DecodeParameters(const DecodeArguments& arguments);

}  // namespace lfsp::cli
