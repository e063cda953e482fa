#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/core/light_field.h"
#include "lfsp/decode/lenslet_decoder.h"

namespace lfsp::decode {

struct CaptureDecodeOptions {
  // Folder of white images (MOD_*.RAW + .TXT, calibration archives). Empty: the capture's own folder, searched
  // recursively, so its whites/ sub-folder is found too.
  std::filesystem::path white_images;
  DecodeOptions decode;
};

struct CaptureDecodeResult {
  LightField light_field;
  nlohmann::json summary;  // capture, the white image used and why, the grid model, the decoder's report, timings
};

// `lfsp decode` as a library call: opens the capture (lfsp::Error "... no raw image ..." for focus-stack or depth
// exports, and for white images), picks its white image (same serial, then nearest zoom step, then nearest focus
// step; lfsp::Error when none matches), fits the lenslet grid on it and decodes.
CaptureDecodeResult DecodeCaptureFile(const std::filesystem::path& capture_path, const CaptureDecodeOptions& options);

}  // namespace lfsp::decode
