#include "view/viewer_data.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <opencv2/core.hpp>

#include "input_loading.h"
#include "lfsp/core/error.h"
#include "lfsp/core/pfm.h"
#include "lfsp/core/visualize.h"
#include "lfsp/depth/depth_io.h"
#include "view_selection.h"

namespace lfsp::view {
namespace fs = std::filesystem;

namespace {

constexpr const char* kPipelineLightField = "segmentation.h5";
constexpr const char* kPipelineDisparity = "disparity.pfm";

void RequireExists(const fs::path& path, const std::string& what) {
  std::error_code ec;
  if (!path.empty() && !fs::exists(path, ec)) ThrowFileError(path.string(), what + " not found");
}

// The confidence `lfsp depth` writes beside a disparity, when it is there.
fs::path ConfidenceBeside(const fs::path& disparity) {
  if (disparity.empty()) return {};
  const fs::path confidence = depth::OutputPathsFor(disparity).confidence;
  std::error_code ec;
  return fs::exists(confidence, ec) ? confidence : fs::path();
}

// The page draws a centre-view map over every view: it must have the views' size.
void RequireViewSize(const std::optional<DisparityMap>& map, const fs::path& path, const LightFieldShape& shape) {
  if (!map || (map->width() == shape.width && map->height() == shape.height)) return;
  ThrowFileError(path.empty() ? "the input's disparity" : path.string(),
                 "a map of " + std::to_string(map->width()) + "x" + std::to_string(map->height()) +
                     " does not match views of " + std::to_string(shape.width) + "x" + std::to_string(shape.height));
}

std::vector<std::uint8_t> DisplayViews(const LightField& light_field) {
  const LightFieldShape& shape = light_field.shape();
  std::vector<std::uint8_t> bytes(shape.Views() * shape.ViewPixels() * 3);
  for (int v = 0; v < shape.nv; ++v) {
    for (int u = 0; u < shape.nu; ++u) {
      const cv::Mat view = DisplayRgb8(light_field.View({u, v}), light_field.transfer);
      cv::Mat rgb = view;
      if (view.channels() == 1) cv::merge(std::vector<cv::Mat>{view, view, view}, rgb);
      const cv::Mat continuous = rgb.isContinuous() ? rgb : rgb.clone();
      const std::size_t offset = (static_cast<std::size_t>(v) * shape.nu + u) * shape.ViewPixels() * 3;
      std::memcpy(bytes.data() + offset, continuous.data, shape.ViewPixels() * 3);
    }
  }
  return bytes;
}

// Labels in the narrowest of uint16/int32 that holds them; unlabelled (-1) becomes the type's largest value,
// which no label reaches.
std::vector<std::uint8_t> PackLabels(const Labels& labels, int& label_bytes) {
  const std::int32_t* begin = labels.data();
  const std::int32_t largest = labels.size() == 0 ? 0 : *std::max_element(begin, begin + labels.size());
  label_bytes = largest < std::numeric_limits<std::uint16_t>::max() ? 2 : 4;
  std::vector<std::uint8_t> bytes(labels.size() * static_cast<std::size_t>(label_bytes));
  if (label_bytes == 2) {
    auto* out = reinterpret_cast<std::uint16_t*>(bytes.data());
    for (std::size_t i = 0; i < labels.size(); ++i)
      out[i] = begin[i] < 0 ? std::numeric_limits<std::uint16_t>::max() : static_cast<std::uint16_t>(begin[i]);
  } else {
    auto* out = reinterpret_cast<std::int32_t*>(bytes.data());
    for (std::size_t i = 0; i < labels.size(); ++i)
      out[i] = begin[i] < 0 ? std::numeric_limits<std::int32_t>::max() : begin[i];
  }
  return bytes;
}

nlohmann::json MetaOf(const ViewerData& data) {
  const LightFieldShape& shape = data.bundle.light_field.shape();
  nlohmann::json meta = {{"input", data.sources.light_field.string()},
                         {"nu", shape.nu},
                         {"nv", shape.nv},
                         {"width", shape.width},
                         {"height", shape.height},
                         {"transfer", ToString(data.bundle.light_field.transfer)},
                         {"label_bytes", data.label_bytes},
                         {"has_disparity", data.bundle.disparity.has_value()},
                         {"has_confidence", data.confidence.has_value()}};
  if (data.bundle.labels && data.bundle.labels->size() > 0) {
    const Labels& labels = *data.bundle.labels;
    meta["largest_label"] = *std::max_element(labels.data(), labels.data() + labels.size());
  }
  if (!data.sources.labels.empty()) meta["labels"] = data.sources.labels.string();
  if (!data.sources.disparity.empty()) meta["disparity"] = data.sources.disparity.string();
  return meta;
}

}  // namespace

ViewerSources ResolveSources(const fs::path& input, const fs::path& labels, const fs::path& disparity) {
  RequireExists(input, "input");
  RequireExists(labels, "labels file");
  RequireExists(disparity, "disparity file");
  ViewerSources sources{input, labels, disparity, ConfidenceBeside(disparity)};
  std::error_code ec;
  if (fs::is_directory(input, ec) && fs::exists(input / kPipelineLightField, ec)) {
    sources.light_field = input / kPipelineLightField;
    if (disparity.empty() && fs::exists(input / kPipelineDisparity, ec)) {
      sources.disparity = input / kPipelineDisparity;
      sources.confidence = ConfidenceBeside(sources.disparity);
    }
  }
  return sources;
}

ViewerData LoadViewerData(const ViewerSources& sources) {
  ViewerData data;
  data.sources = sources;
  data.recolor_base.input = sources.light_field.string();
  data.recolor_base.labels = sources.labels.string();
  data.bundle = cli::LoadInput(sources.light_field);
  if (data.bundle.labels || !sources.labels.empty()) {
    nlohmann::ordered_json loading;
    cli::AttachLabels(data.bundle, data.recolor_base, loading);
  } else {
    // No labels anywhere: the light field can still be looked at (and refocused), not edited.
    cli::SelectViews(data.bundle, 0, sources.light_field.string());
    spdlog::info("{}: no labels: viewing only (give --labels SEG.h5 to select and edit)", sources.light_field.string());
  }
  if (!sources.disparity.empty()) data.bundle.disparity = ReadPfm(sources.disparity);
  if (!sources.confidence.empty()) data.confidence = ReadPfm(sources.confidence);
  RequireViewSize(data.bundle.disparity, sources.disparity, data.bundle.light_field.shape());
  RequireViewSize(data.confidence, sources.confidence, data.bundle.light_field.shape());
  data.views_rgb8 = DisplayViews(data.bundle.light_field);
  if (data.bundle.labels) data.labels_packed = PackLabels(*data.bundle.labels, data.label_bytes);
  data.meta = MetaOf(data);
  return data;
}

std::string FloatBytes(const std::optional<DisparityMap>& map) {
  if (!map) return {};
  return std::string(reinterpret_cast<const char*>(map->data()),
                     static_cast<std::size_t>(map->width()) * static_cast<std::size_t>(map->height()) * sizeof(float));
}

}  // namespace lfsp::view
