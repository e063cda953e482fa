#include "lfsp/core/views_folder.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <opencv2/core.hpp>
#include <regex>

#include "lfsp/core/atomic_file.h"
#include "lfsp/core/error.h"
#include "lfsp/core/hci_config.h"
#include "lfsp/core/image_io.h"
#include "lfsp/core/input_limits.h"
#include "views_folder_internal.h"

namespace lfsp {
namespace fs = std::filesystem;

namespace {

constexpr const char* kConfigName = "parameters.cfg";

std::string ViewFileName(const char* prefix, int camera, const std::string& extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_Cam%03d%s", prefix, camera, extension.c_str());
  return name;
}

// input_CamNNN.<ext> files of the folder, by camera number.
std::map<int, fs::path> FindViewFiles(const fs::path& folder, const char* prefix) {
  static const std::regex kPattern("_Cam([0-9]{3,4})\\.(png|PNG|tif|tiff|TIF|exr|jpg|jpeg)");
  std::map<int, fs::path> views;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    std::smatch match;
    const std::string rest = name.substr(std::string(prefix).size());
    if (!std::regex_match(rest, match, kPattern)) continue;
    const int camera = std::stoi(match[1].str());
    if (views.count(camera)) ThrowFileError(entry.path().string(), "two files for camera " + match[1].str());
    views[camera] = entry.path();
  }
  return views;
}

// Angular size from parameters.cfg (num_cams_x/num_cams_y), else the square root of the view count.
ViewIndex AngularSize(const Metadata& metadata, std::size_t view_count, const fs::path& folder) {
  if (metadata.contains("extrinsics")) {
    const Metadata& extrinsics = metadata["extrinsics"];
    if (extrinsics.contains("num_cams_x") && extrinsics.contains("num_cams_y") &&
        extrinsics["num_cams_x"].is_number_integer() && extrinsics["num_cams_y"].is_number_integer()) {
      // Read wide: 4294967303 must not wrap to 7.
      const long long nu = extrinsics["num_cams_x"].get<long long>();
      const long long nv = extrinsics["num_cams_y"].get<long long>();
      if (nu <= 0 || nv <= 0 || nu > 64 || nv > 64)
        ThrowFileError((folder / kConfigName).string(), "num_cams_x/num_cams_y out of range");
      return {static_cast<int>(nu), static_cast<int>(nv)};
    }
  }
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(view_count))));
  if (static_cast<std::size_t>(side * side) != view_count)
    ThrowFileError(folder.string(), std::to_string(view_count) +
                                        " views do not form a square grid and parameters.cfg gives no num_cams_x/y");
  return {side, side};
}

Transfer TransferFromMetadata(const Metadata& metadata) {
  if (metadata.contains("lfsp") && metadata["lfsp"].contains("transfer") && metadata["lfsp"]["transfer"].is_string())
    return TransferFromString(metadata["lfsp"]["transfer"].get<std::string>());
  return Transfer::kSrgb;  // what PNG views from renderers and cameras hold
}

// Runs `body(i)` for i in [0, count) on all cores; the first exception is rethrown after the loop.
template <typename Body>
void ParallelForEachView(int count, Body body) {
  std::exception_ptr failure;
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < count; ++i) {
    try {
      body(i);
    } catch (...) {
#pragma omp critical(lfsp_views_failure)
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace

bool LooksLikeViewsFolder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return false;
  return fs::exists(folder / ViewFileName("input", 0, ".png"), ec) || fs::exists(folder / kConfigName, ec) ||
         !FindViewFiles(folder, "input").empty();
}

LightField ReadViewsFolder(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) ThrowFileError(folder.string(), "not a folder of views");
  const Metadata metadata =
      fs::exists(folder / kConfigName, ec) ? ReadHciConfig(folder / kConfigName) : Metadata::object();
  const std::map<int, fs::path> files = FindViewFiles(folder, "input");
  if (files.empty()) ThrowFileError(folder.string(), "no views (input_Cam000.png ...) found");
  const ViewIndex angular = AngularSize(metadata, files.size(), folder);
  const int view_count = angular.u * angular.v;
  for (int camera = 0; camera < view_count; ++camera) {
    if (!files.count(camera))
      ThrowFileError((folder / ViewFileName("input", camera, ".png")).string(),
                     "missing view " + std::to_string(camera) + " of " + std::to_string(view_count));
  }
  if (static_cast<int>(files.size()) != view_count || files.rbegin()->first != view_count - 1)
    ThrowFileError(folder.string(), "found " + std::to_string(files.size()) + " views, expected " +
                                        std::to_string(view_count) + " (" + std::to_string(angular.u) + "x" +
                                        std::to_string(angular.v) + ")");

  // Every header is read, and the sizes they declare checked against the files, before anything is allocated.
  const ImageHeader first = ReadImageHeader(files.at(0));
  std::uint64_t file_bytes = 0;
  for (const auto& [camera, path] : files) {
    const ImageHeader header = camera == 0 ? first : ReadImageHeader(path);
    if (header.width != first.width || header.height != first.height)
      ThrowFileError(path.string(), "image is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                                        ", expected " + std::to_string(first.width) + "x" +
                                        std::to_string(first.height) + " like " + files.at(0).filename().string());
    file_bytes += FileBytes(path);
  }
  LightFieldShape shape;
  shape.nu = angular.u;
  shape.nv = angular.v;
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
  light_field.transfer = TransferFromMetadata(metadata);

  ParallelForEachView(view_count, [&](int camera) {
    cv::Mat view = light_field.View(ViewFromCameraNumber(camera, shape.nu));
    ReadImageInto(files.at(camera), view);
  });

  const std::map<int, fs::path> weight_files = FindViewFiles(folder, "weight");
  if (static_cast<int>(weight_files.size()) == view_count) {
    light_field.EnableWeights();
    ParallelForEachView(view_count, [&](int camera) {
      cv::Mat weights = light_field.WeightView(ViewFromCameraNumber(camera, shape.nu));
      ReadImageInto(weight_files.at(camera), weights);
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
  const LightFieldShape& shape = light_field.shape();
  const int view_count = static_cast<int>(shape.Views());
  ParallelForEachView(view_count, [&](int camera) {
    const ViewIndex view = ViewFromCameraNumber(camera, shape.nu);
    WriteImage(light_field.View(view), folder / ViewFileName("input", camera, ".png"), options.bit_depth,
               {{"oiio:ColorSpace", light_field.transfer == Transfer::kSrgb ? "sRGB" : "linear"}});
    if (light_field.HasWeights()) {
      const cv::Mat weights(shape.height, shape.width, CV_32FC1,
                            const_cast<float*>(light_field.weights().ViewData(view)));
      WriteImage(weights, folder / ViewFileName("weight", camera, ".png"), 16);
    }
  });

  Metadata metadata = light_field.metadata.is_object() ? light_field.metadata : Metadata::object();
  metadata["extrinsics"]["num_cams_x"] = shape.nu;
  metadata["extrinsics"]["num_cams_y"] = shape.nv;
  metadata["intrinsics"]["image_resolution_x_px"] = shape.width;
  metadata["intrinsics"]["image_resolution_y_px"] = shape.height;
  metadata["lfsp"]["transfer"] = ToString(light_field.transfer);
  AtomicOutput config(folder / kConfigName);
  {
    std::FILE* file = std::fopen(config.temporary().c_str(), "wb");
    if (!file) ThrowFileError((folder / kConfigName).string(), "cannot create");
    const std::string text = FormatHciConfig(metadata);
    const bool ok = std::fwrite(text.data(), 1, text.size(), file) == text.size();
    if (std::fclose(file) != 0 || !ok) ThrowFileError((folder / kConfigName).string(), "write failed");
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
