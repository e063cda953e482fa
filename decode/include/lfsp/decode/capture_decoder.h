#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "lfsp/core/light_field.h"
#include "lfsp/decode/lenslet_decoder.h"
#include "lfsp/decode/raw_input.h"

namespace lfsp::decode {

struct CaptureDecodeOptions {
  // Folder of white images (MOD_*.RAW + .TXT, calibration archives). Empty: the capture's own folder, searched
  // recursively, so its whites/ sub-folder is found too.
  std::filesystem::path white_images;
  // Estimate the white image from the capture itself (EstimateWhiteImageFromCapture) and find the lattice in the
  // capture (EstimateLensletGridFromCapture) instead of looking one up. Also what happens, with a warning, when no
  // white image matches, and always for plain raw images.
  bool no_white_image = false;
  // A lenslet grid to use instead of fitting one (ReadGivenGrid: lfsp's grid.json or LFToolbox's LensletGridModel,
  // e.g. a CalInfo.json). The white image is still looked up or estimated, for devignetting.
  std::filesystem::path grid;
  PlainRawOptions plain;  // how to read a plain raw image (PNG/TIFF/JPEG Bayer mosaic)
  DecodeOptions decode;
};

struct CaptureDecodeResult {
  LightField light_field;
  nlohmann::json summary;  // capture, the white image used and why, the grid model, the decoder's report, timings
};

// `lfsp decode` as a library call: opens the capture (any RawInput; lfsp::Error "... no raw image ..." for
// focus-stack or depth exports, for white images, and for plain images without a camera), picks its white image
// (same serial, then nearest zoom step, then nearest focus step), fits the lenslet grid on it and decodes. Without a
// matching white image it warns and estimates one from the capture (see no_white_image); an explicitly given
// white-image folder that does not exist is an lfsp::Error.
CaptureDecodeResult DecodeCaptureFile(const std::filesystem::path& capture_path, const CaptureDecodeOptions& options);

}  // namespace lfsp::decode
