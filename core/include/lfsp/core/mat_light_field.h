#pragma once

// MATLAB .mat light fields, as LFToolbox and the deep-learning repositories (BasicLFSR and others) keep them.
//
// Both hold one 5-D variable `LF` indexed, in MATLAB's 1-based column-major order, LF(v, u, y, x, c): v the angular
// row, u the angular column, y the pixel row, x the pixel column, c the channel. LFToolbox calls it LF(j,i,l,k,c)
// and adds a 4th channel, the ray weight; the deep-learning files ([U,V,H,W,3]) have 3. Samples are uint8, uint16
// (scaled by the type's maximum), single or double (taken as they are, in [0, 1]).
//
// - v5/v7 files are read with libmatio. Declared sizes are checked against the file before the data is read.
// - v7.3 files are HDF5: the variable is the dataset `LF`, whose HDF5 shape is MATLAB's reversed (C, W, H, nu, nv)
//   because MATLAB is column-major; h5py shows the same shape. They are read with HDF5 directly.
//
// Written: LFToolbox's layout (uint16, 4 channels with the ray weight, 1 where the light field has none), v5 with
// zlib compression, or v7.3 when the variable is 2 GiB or more (v5's limit), so MATLAB users can go back.

#include <filesystem>

#include "lfsp/core/light_field.h"

namespace lfsp {

LightField ReadMatLightField(const std::filesystem::path& path);
void WriteMatLightField(const LightField& light_field, const std::filesystem::path& path);

}  // namespace lfsp
