#include "lfsp/core/load.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <vector>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/file_names.h"
#include "lfsp/core/mat_light_field.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/views_folder.h"
#include "views_folder_internal.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

// Ground-truth or previously saved disparity stored beside the views.
constexpr const char* kDisparityNames[] = {"disparity.pfm", "gt_disp_lowres.pfm"};

}  // namespace

void RequireFiniteSamples(const LightField& light_field, const std::string& name) {
  const LightFieldShape& shape = light_field.shape();
  const auto first_bad = [](const float* values, std::size_t count) {
    return static_cast<std::size_t>(std::find_if(values, values + count, [](float v) { return !std::isfinite(v); }) -
                                    values);
  };
  const std::size_t bad = first_bad(light_field.data(), light_field.size());
  if (bad != light_field.size()) {
    const std::size_t ray = bad / static_cast<std::size_t>(shape.channels);
    const std::size_t view = ray / shape.ViewPixels(), pixel = ray % shape.ViewPixels();
    const ViewIndex at = ViewFromCameraNumber(static_cast<int>(view), shape.nu);
    ThrowFileError(name, "holds a non-finite sample (NaN or infinity) in view (u " + std::to_string(at.u) + ", v " +
                             std::to_string(at.v) + ") at x " + std::to_string(pixel % shape.width) + ", y " +
                             std::to_string(pixel / shape.width));
  }
  if (!light_field.HasWeights()) return;
  const Array4D<float>& weights = light_field.weights();
  if (first_bad(weights.data(), weights.size()) != weights.size())
    ThrowFileError(name, "holds a non-finite ray weight (NaN or infinity)");
  const float* negative = std::find_if(weights.data(), weights.data() + weights.size(), [](float w) { return w < 0; });
  if (negative != weights.data() + weights.size())
    ThrowFileError(name, "holds a negative ray weight (" + std::to_string(*negative) + "); weights lie in [0, 1]");
}

void RequireUsableDisparityRange(const Metadata& metadata, const std::string& name) {
  if (!metadata.is_object() || !metadata.contains("meta") || !metadata["meta"].is_object()) return;
  const Metadata& meta = metadata["meta"];
  for (const char* key : {"disp_min", "disp_max"}) {
    if (!meta.contains(key)) continue;
    const Metadata& value = meta[key];
    if (!value.is_number() || !std::isfinite(value.get<double>())) {
      // JSON has no NaN or infinity, so dump() writes them as null; parameters.cfg's "nan" is shown as written.
      const double number = value.is_number() ? value.get<double>() : 0.0;
      const std::string shown = !value.is_number()   ? value.dump()
                                : std::isnan(number) ? "nan"
                                : number > 0         ? "inf"
                                                     : "-inf";
      ThrowFileError(name, std::string("metadata field meta.") + key + " = " + shown + " is not a finite number");
    }
  }
  if (const auto range = DisparityRangeFromMetadata(metadata); range && range->min > range->max)
    ThrowFileError(name, "metadata disparity range meta.disp_min " + std::to_string(range->min) + " > meta.disp_max " +
                             std::to_string(range->max));
}

LightFieldFormat DetectLightFieldFormat(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) ThrowFileError(path.string(), "no such file or folder");
  if (fs::is_directory(path, ec)) return LightFieldFormat::kViewsFolder;  // its naming is found when it is read
  const std::string extension = LowerExtension(path);
  if (extension == ".h5" || extension == ".hdf5") return LightFieldFormat::kHdf5Bundle;
  if (extension == ".png" || extension == ".tif" || extension == ".tiff") return LightFieldFormat::kEslf;
  if (extension == ".mat") return LightFieldFormat::kMat;
  ThrowFileError(path.string(),
                 "unknown light-field format (expected a views folder, a .h5 bundle, an ESLF .png or a MATLAB .mat)");
}

namespace {

Bundle ReadAnyFormat(const fs::path& path, const LoadOptions& options) {
  switch (DetectLightFieldFormat(path)) {
    case LightFieldFormat::kHdf5Bundle:
      return ReadBundle(path);
    case LightFieldFormat::kEslf: {
      Bundle bundle;
      bundle.light_field = ReadEslf(path, options.eslf);
      return bundle;
    }
    case LightFieldFormat::kMat: {
      Bundle bundle;
      bundle.light_field = ReadMatLightField(path);
      return bundle;
    }
    case LightFieldFormat::kViewsFolder:
      break;
  }
  Bundle bundle;
  bundle.light_field = ReadViewsFolder(path, options.views_pattern);
  for (const char* name : kDisparityNames) {
    std::error_code ec;
    if (!fs::exists(path / name, ec)) continue;
    DisparityMap disparity = ReadPfm(path / name);
    const LightFieldShape& shape = bundle.light_field.shape();
    if (disparity.width() != shape.width || disparity.height() != shape.height)
      ThrowFileError((path / name).string(), "disparity size does not match the views");
    bundle.disparity = std::move(disparity);
    break;
  }
  return bundle;
}

}  // namespace

Bundle LoadLightField(const fs::path& path, const LoadOptions& options) {
  Bundle bundle = ReadAnyFormat(path, options);
  RequireFiniteSamples(bundle.light_field, path.string());
  RequireUsableDisparityRange(bundle.light_field.metadata, path.string());
  return bundle;
}

LoadedViews LoadCentralViews(const fs::path& path, int requested, const LoadOptions& options) {
  LoadedViews loaded;
  if (DetectLightFieldFormat(path) != LightFieldFormat::kHdf5Bundle) {
    loaded.bundle = LoadLightField(path, options);
    loaded.choice = KeepChosenViews(loaded.bundle.light_field, loaded.bundle.labels, requested);
    return loaded;
  }
  const LightFieldShape shape = ReadBundleShape(path);
  const std::vector<double> means = ReadViewMeanWeights(path);
  std::function<double(ViewIndex)> mean_weight;
  if (!means.empty())
    mean_weight = [&](ViewIndex view) { return means[static_cast<std::size_t>(view.v * shape.nu + view.u)]; };
  loaded.choice = ChooseViews(shape, mean_weight, requested);
  BundleParts parts;
  parts.views = CentralViewBlock(shape, loaded.choice.n);
  loaded.bundle = ReadBundle(path, parts);
  RequireFiniteSamples(loaded.bundle.light_field, path.string());
  RequireUsableDisparityRange(loaded.bundle.light_field.metadata, path.string());
  return loaded;
}

void SaveLightField(const Bundle& bundle, const fs::path& path, int bit_depth, const std::string& view_extension) {
  const std::string extension = LowerExtension(path);
  if (extension == ".h5" || extension == ".hdf5") {
    WriteBundle(bundle, path, CompactBundleOptions(bundle.light_field));
    return;
  }
  if (extension == ".mat") {
    WriteMatLightField(bundle.light_field, path);
    return;
  }
  if (extension == ".png" || extension == ".tif" || extension == ".tiff") {
    EslfOptions options;
    options.bit_depth = bit_depth;
    WriteEslf(bundle.light_field, path, options);
    return;
  }
  // Anything else is a views folder; a name with a file type's extension is a mistake, not a folder to create.
  for (const char* file_type : {".pfm", ".jpg", ".jpeg", ".json", ".csv", ".txt", ".exr", ".bmp", ".gif", ".mp4",
                                ".lfp", ".lfr", ".raw", ".npy", ".npz"})
    if (extension == file_type)
      throw Error(path.string() + ": " + extension +
                  " is not a light-field format (write a views folder, a .h5 bundle, an ESLF .png/.tif or a .mat)");
  internal::CheckReplaceableOutputFolder(path);
  AtomicOutput output(path);
  fs::create_directories(output.temporary());
  ViewsFolderOptions options;
  options.bit_depth = bit_depth;
  options.extension = view_extension;
  internal::WriteViewsInto(bundle.light_field, output.temporary(), options);
  if (bundle.disparity) WritePfm(*bundle.disparity, output.temporary() / kDisparityNames[0]);
  output.Commit();
}

}  // namespace lfsp
