#include "lfsp/core/views_folder.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <opencv2/core.hpp>

#include <spdlog/spdlog.h>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hci_config.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/input_limits.h"
#include "lfsp/core/load.h"
#include "lfsp/core/parallel_for.h"
#include "lfsp/core/views_naming.h"
#include "views_folder_internal.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

// parameters.cfg's [lfsp] transfer. A value that names no transfer function is the file's fault, so the message
// names the file (TransferFromString's alone named neither file nor folder; a number was taken for sRGB).
Transfer TransferFromConfig(const Metadata& metadata, const fs::path& config) {
  if (!metadata.contains("lfsp") || !metadata["lfsp"].is_object() || !metadata["lfsp"].contains("transfer"))
    return Transfer::kSrgb;  // what PNG views from renderers and cameras hold
  const Metadata& value = metadata["lfsp"]["transfer"];
  if (!value.is_string())
    ThrowFileError(config.string(), "[lfsp] transfer = " + value.dump() + ": expected 'linear' or 'srgb'");
  return TransferFromFile(value.get<std::string>(), config.string(), "[lfsp] transfer");
}

}  // namespace

bool LooksLikeViewsFolder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  if (fs::exists(folder / internal::kConfigName, ec)) return true;
  try {
    FindViewsLayout(folder);
    return true;
  } catch (const Error&) {
    return false;
  }
}

LightField ReadViewsFolder(const fs::path& folder, const std::string& views_pattern) {
  const ViewsLayout layout = FindViewsLayout(folder, views_pattern);
  std::error_code ec;
  const fs::path config = folder / internal::kConfigName;
  const Metadata metadata = fs::exists(config, ec) ? ReadHciConfig(config) : Metadata::object();
  // What parameters.cfg says is checked before any view is read, and a value lfsp cannot use named with the file.
  const Transfer transfer = TransferFromConfig(metadata, config);
  RequireUsableDisparityRange(metadata, config.string());
  const int view_count = layout.nu * layout.nv;
  spdlog::info("{}: {}", folder.string(), layout.description);

  // Every header is read, and the sizes they declare checked against the files, before anything is allocated.
  const ImageHeader first = ReadImageHeader(layout.files.front());
  std::uint64_t file_bytes = 0;
  for (const fs::path& path : layout.files) {
    const ImageHeader header = path == layout.files.front() ? first : ReadImageHeader(path);
    if (header.width != first.width || header.height != first.height)
      ThrowFileError(path.string(), "image is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                                        ", expected " + std::to_string(first.width) + "x" +
                                        std::to_string(first.height) + " like " +
                                        layout.files.front().filename().string());
    file_bytes += FileBytes(path);
  }
  LightFieldShape shape;
  shape.nu = layout.nu;
  shape.nv = layout.nv;
  shape.width = first.width;
  shape.height = first.height;
  shape.channels = std::min(first.channels, 3);
  CheckDeclaredAllocation(
      folder.string(),
      SaturatingBytes({static_cast<std::uint64_t>(view_count), static_cast<std::uint64_t>(shape.width),
                       static_cast<std::uint64_t>(shape.height), static_cast<std::uint64_t>(shape.channels)},
                      sizeof(float)),
      file_bytes);
  LightField light_field(shape);
  light_field.metadata = metadata;
  light_field.transfer = transfer;

  ParallelFor(view_count, [&](int camera) {
    cv::Mat view = light_field.View(ViewFromCameraNumber(camera, shape.nu));
    ReadImageInto(layout.files[static_cast<std::size_t>(camera)], view);
  });
  if (static_cast<int>(layout.weight_files.size()) == view_count) {
    light_field.EnableWeights();
    ParallelFor(view_count, [&](int camera) {
      cv::Mat weights = light_field.WeightView(ViewFromCameraNumber(camera, shape.nu));
      ReadImageInto(layout.weight_files[static_cast<std::size_t>(camera)], weights);
    });
  }
  return light_field;
}

namespace internal {

void CheckReplaceableOutputFolder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::exists(folder, ec)) return;
  if (!fs::is_directory(folder, ec))
    ThrowFileError(folder.string(), "exists and is not a folder; refusing to replace it with a views folder");
  if (!fs::is_empty(folder, ec) && !LooksLikeViewsFolder(folder))
    ThrowFileError(folder.string(), "exists, is not empty and holds no light field; refusing to replace it");
}

void WriteViewsInto(const LightField& light_field, const fs::path& folder, const ViewsFolderOptions& options) {
  if (options.bit_depth != 8 && options.bit_depth != 16)
    throw Error("views folder bit depth must be 8 or 16, not " + std::to_string(options.bit_depth));
  if (options.extension != ".png" && options.extension != ".tif")
    throw Error("views folder format must be .png or .tif, not " + options.extension);
  const LightFieldShape& shape = light_field.shape();
  const int view_count = static_cast<int>(shape.Views());
  ParallelFor(view_count, [&](int camera) {
    const ViewIndex view = ViewFromCameraNumber(camera, shape.nu);
    WriteImage(light_field.View(view), folder / internal::HciViewFileName("input", camera, options.extension),
               options.bit_depth, {{"oiio:ColorSpace", light_field.transfer == Transfer::kSrgb ? "sRGB" : "linear"}});
    if (light_field.HasWeights()) {
      const cv::Mat weights(shape.height, shape.width, CV_32FC1,
                            const_cast<float*>(light_field.weights().ViewData(view)));
      WriteImage(weights, folder / internal::HciViewFileName("weight", camera, ".png"), 16);
    }
  });

  Metadata metadata = light_field.metadata.is_object() ? light_field.metadata : Metadata::object();
  metadata["extrinsics"]["num_cams_x"] = shape.nu;
  metadata["extrinsics"]["num_cams_y"] = shape.nv;
  metadata["intrinsics"]["image_resolution_x_px"] = shape.width;
  metadata["intrinsics"]["image_resolution_y_px"] = shape.height;
  metadata["lfsp"]["transfer"] = ToString(light_field.transfer);
  AtomicOutput config(folder / internal::kConfigName);
  {
    std::FILE* file = std::fopen(config.temporary().c_str(), "wb");
    if (!file) ThrowFileError((folder / internal::kConfigName).string(), "cannot create");
    const std::string text = FormatHciConfig(metadata);
    const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    if (std::fclose(file) != 0 || !ok) ThrowFileError((folder / internal::kConfigName).string(), "write failed");
  }
  config.Commit();
}

}  // namespace internal

void WriteViewsFolder(const LightField& light_field, const fs::path& folder, const ViewsFolderOptions& options) {
  internal::CheckReplaceableOutputFolder(folder);
  AtomicOutput output(folder);
  fs::create_directories(output.temporary());
  internal::WriteViewsInto(light_field, output.temporary(), options);
  output.Commit();
}

}  // namespace lfsp
