#include "lfsp/core/load.h"

#include <algorithm>
#include <cctype>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/views_folder.h"
#include "views_folder_internal.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

std::string LowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// Ground-truth or previously saved disparity stored beside the views.
constexpr const char* kDisparityNames[] = {"disparity.pfm", "gt_disp_lowres.pfm"};

}  // namespace

LightFieldFormat DetectLightFieldFormat(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) ThrowFileError(path.string(), "no such file or folder");
  if (fs::is_directory(path, ec)) {
    if (!LooksLikeViewsFolder(path))
      ThrowFileError(path.string(), "folder holds no light-field views (input_Cam000.png ...)");
    return LightFieldFormat::kViewsFolder;
  }
  const std::string extension = LowerExtension(path);
  if (extension == ".h5" || extension == ".hdf5") return LightFieldFormat::kHdf5Bundle;
  if (extension == ".png" || extension == ".tif" || extension == ".tiff") return LightFieldFormat::kEslf;
  ThrowFileError(path.string(), "unknown light-field format (expected a views folder, a .h5 bundle or an ESLF .png)");
}

Bundle LoadLightField(const fs::path& path, const EslfOptions& eslf) {
  switch (DetectLightFieldFormat(path)) {
    case LightFieldFormat::kHdf5Bundle:
      return ReadBundle(path);
    case LightFieldFormat::kEslf: {
      Bundle bundle;
      bundle.light_field = ReadEslf(path, eslf);
      return bundle;
    }
    case LightFieldFormat::kViewsFolder:
      break;
  }
  Bundle bundle;
  bundle.light_field = ReadViewsFolder(path);
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

void SaveLightField(const Bundle& bundle, const fs::path& path, int bit_depth) {
  const std::string extension = LowerExtension(path);
  if (extension == ".h5" || extension == ".hdf5") {
    WriteBundle(bundle, path, CompactBundleOptions(bundle.light_field));
    return;
  }
  if (extension == ".png" || extension == ".tif" || extension == ".tiff") {
    EslfOptions options;
    options.bit_depth = bit_depth;
    WriteEslf(bundle.light_field, path, options);
    return;
  }
  internal::CheckReplaceableOutputFolder(path);
  AtomicOutput output(path);
  fs::create_directories(output.temporary());
  ViewsFolderOptions options;
  options.bit_depth = bit_depth;
  internal::WriteViewsInto(bundle.light_field, output.temporary(), options);
  if (bundle.disparity) WritePfm(*bundle.disparity, output.temporary() / kDisparityNames[0]);
  output.Commit();
}

}  // namespace lfsp
