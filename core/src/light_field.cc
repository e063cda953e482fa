#include "lfsp/core/light_field.h"

#include <opencv2/core.hpp>
#include <unordered_map>

#include "lfsp/core/error.h"

namespace lfsp {

std::string ToString(Transfer transfer) { return transfer == Transfer::kLinear ? "linear" : "srgb"; }

Transfer TransferFromString(const std::string& name) {
  if (name == "linear") return Transfer::kLinear;
  if (name == "srgb") return Transfer::kSrgb;
  throw Error("unknown transfer function '" + name + "' (expected 'linear' or 'srgb')");
}

Transfer TransferFromFile(const std::string& name, const std::string& file, const std::string& where) {
  try {
    return TransferFromString(name);
  } catch (const Error& error) {
    ThrowFileError(file, where + ": " + error.what());
  }
}

std::string ToString(const LightFieldShape& shape) {
  return std::to_string(shape.nv) + "x" + std::to_string(shape.nu) + " views of " + std::to_string(shape.height) + "x" +
         std::to_string(shape.width) + "x" + std::to_string(shape.channels);
}

namespace {
// cv::Mat needs a non-const pointer even for read-only use; the const overloads document that contract.
template <typename T>
cv::Mat WrapView(const LightFieldShape& shape, int depth, int channels, const T* data) {
  return cv::Mat(shape.height, shape.width, CV_MAKETYPE(depth, channels), const_cast<T*>(data));
}

LightFieldShape OneChannel(LightFieldShape shape) {
  shape.channels = 1;
  return shape;
}
}  // namespace

cv::Mat LightField::View(ViewIndex view) { return WrapView(shape_, CV_32F, shape_.channels, ViewData(view)); }
cv::Mat LightField::View(ViewIndex view) const { return WrapView(shape_, CV_32F, shape_.channels, ViewData(view)); }

void LightField::EnableWeights(float fill) { weights_ = Array4D<float>(OneChannel(shape_), fill); }

void LightField::EnableWeights(Unfilled) { weights_ = Array4D<float>(OneChannel(shape_), Unfilled{}); }

cv::Mat LightField::WeightView(ViewIndex view) {
  return WrapView(weights_.shape(), CV_32F, 1, weights_.ViewData(view));
}

Labels::Labels(LightFieldShape shape, std::int32_t fill) : Array4D<std::int32_t>(OneChannel(shape), fill) {}

Labels::Labels(LightFieldShape shape, Unfilled) : Array4D<std::int32_t>(OneChannel(shape), Unfilled{}) {}

cv::Mat Labels::View(ViewIndex view) { return WrapView(shape_, CV_32S, 1, ViewData(view)); }
cv::Mat Labels::View(ViewIndex view) const { return WrapView(shape_, CV_32S, 1, ViewData(view)); }

void RequireValidLabelValues(const Labels& labels, const std::string& where) {
  const std::int32_t* values = labels.data();
  for (std::size_t i = 0; i < labels.size(); ++i)
    if (values[i] < Labels::kUnlabelled)
      ThrowFileError(
          where, "holds label " + std::to_string(values[i]) + "; labels are -1 (unlabelled) or non-negative integers");
}

void RequireLabelsMatch(const Labels& labels, const LightFieldShape& shape, const std::string& what) {
  const LightFieldShape& have = labels.shape();
  if (have.nu != shape.nu || have.nv != shape.nv || have.width != shape.width || have.height != shape.height)
    throw Error(what + ": labels are " + std::to_string(have.nv) + "x" + std::to_string(have.nu) + " views of " +
                std::to_string(have.width) + "x" + std::to_string(have.height) + " but the light field is " +
                ToString(shape));
}

Labels DenselyRelabelled(const Labels& labels) {
  Labels out(labels.shape());
  std::unordered_map<std::int32_t, std::int32_t> dense;
  const std::int32_t* in = labels.data();
  std::int32_t* o = out.data();
  for (std::size_t i = 0; i < labels.size(); ++i) {
    if (in[i] < 0) continue;  // stays kUnlabelled
    o[i] = dense.try_emplace(in[i], static_cast<std::int32_t>(dense.size())).first->second;
  }
  return out;
}

DisparityMap::DisparityMap(int width, int height, float fill)
    : width_(width),
      height_(height),
      values_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill) {}

cv::Mat DisparityMap::Mat() { return cv::Mat(height_, width_, CV_32FC1, values_.data()); }
cv::Mat DisparityMap::Mat() const { return cv::Mat(height_, width_, CV_32FC1, const_cast<float*>(values_.data())); }

}  // namespace lfsp
