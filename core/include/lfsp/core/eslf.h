#pragma once

#include <filesystem>
#include <optional>

#include "lfsp/core/light_field.h"

namespace lfsp {

// ESLF ("encoded sub-aperture light field", Stanford Lytro archive / LFToolbox): one image of (width*nu) x
// (height*nv) pixels where the macro-pixel of spatial sample (x, y) holds all nu x nv angular samples:
// image(y*nv + v, x*nu + u) = view(u, v)(y, x).
//
// The angular size cannot be inferred from the pixels. It is stored in the PNG as text attributes
// (lfsp:nu / lfsp:nv); for files written elsewhere pass it explicitly (the Stanford archive uses 14x14).
struct EslfOptions {
  std::optional<int> nu;
  std::optional<int> nv;
  int bit_depth = 8;  // for writing: 8 or 16
};

LightField ReadEslf(const std::filesystem::path& path, const EslfOptions& options = {});
void WriteEslf(const LightField& light_field, const std::filesystem::path& path, const EslfOptions& options = {});

}  // namespace lfsp
