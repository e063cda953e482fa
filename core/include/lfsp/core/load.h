#pragma once

#include <filesystem>
#include <string>

#include "lfsp/core/eslf.h"
#include "lfsp/core/hdf5_bundle.h"
#include "lfsp/core/metadata.h"
#include "lfsp/core/view_crop.h"

namespace lfsp {

// Which project format a path holds, judged by what it is (folder, extension, magic).
enum class LightFieldFormat { kViewsFolder, kHdf5Bundle, kEslf, kMat };

LightFieldFormat DetectLightFieldFormat(const std::filesystem::path& path);  // throws lfsp::Error if none

// Loads any supported light-field input into a bundle. For a views folder, a ground-truth disparity PFM beside the
// views (gt_disp_lowres.pfm, as in the HCI benchmark) is loaded as the bundle's disparity. A light field holding a
// NaN or infinite sample or ray weight is refused (lfsp::Error naming the file and the first such ray).
// NaN or infinite samples have no meaning as light: every stage would turn them into silent garbage (a constant
// depth map, all-NaN scores), so a light field holding one is refused: lfsp::Error naming `name` and the first such
// ray. A negative ray weight is refused too: weights are how much of a ray the sensor saw, and every weighted mean
// divides by their sum. Finite samples outside [0, 1] (-5, say) are kept: scene-linear decodes legitimately hold
// values below 0 and above 1 after the colour matrix, and every stage computes with any finite value.
// LoadLightField checks every input so; so does the Python module for arrays it is given.
void RequireFiniteSamples(const LightField& light_field, const std::string& name);

// A disparity range in the metadata (meta.disp_min / meta.disp_max) that is present but not two finite numbers with
// min <= max is refused (lfsp::Error naming `name`): `"disp_min": "low"` was ignored without a word, and the range
// estimated instead of the one the file declares. LoadLightField checks every input so.
void RequireUsableDisparityRange(const Metadata& metadata, const std::string& name);

struct LoadOptions {
  EslfOptions eslf;           // the angular size of an ESLF image that does not record it
  std::string views_pattern;  // views folders: file naming such as '{row}_{col}.png' ("" = detect, views_naming.h)
};
Bundle LoadLightField(const std::filesystem::path& path, const LoadOptions& options = {});

// LoadLightField keeping only the views ChooseViews picks (`requested` > 0: the central requested x requested). An
// .h5 bundle is read only for those views: its views' mean weights first (ReadViewMeanWeights), then the central
// block, so a stage that keeps 9x9 of a 15x15 decode never holds the 15x15 (issue 46). Other formats are read whole
// and cropped. Either way the same light field, labels and disparity as loading everything and cropping; only the
// kept views' samples are checked (RequireFiniteSamples).
struct LoadedViews {
  Bundle bundle;
  ViewChoice choice;
};
LoadedViews LoadCentralViews(const std::filesystem::path& path, int requested, const LoadOptions& options = {});

// Writes the light field in the format chosen by the output path: `.h5` -> bundle, `.png` -> ESLF, `.mat` ->
// LFToolbox's LF(v, u, y, x, c) with the weight channel (mat_light_field.h), else a views
// folder (the disparity, if any, goes beside the views as disparity.pfm); a name with the extension of another
// file type (.pfm, .jpg, .json, ...) is refused rather than made a folder.
// `view_extension` (".png" or ".tif") is the views folder's file type.
void SaveLightField(const Bundle& bundle, const std::filesystem::path& path, int bit_depth = 8,
                    const std::string& view_extension = ".png");

}  // namespace lfsp
