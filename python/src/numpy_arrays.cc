#include "numpy_arrays.h"

#include <algorithm>
#include <memory>

#include "lfsp/core/error.h"
#include "lfsp/core/load.h"

namespace lfsp::python {
namespace {

template <typename T>
std::vector<py::ssize_t> ContiguousStrides(const std::vector<py::ssize_t>& shape) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(T);
  for (std::size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  return strides;
}

// A capsule that deletes `object` when the last array over it goes.
template <typename T>
py::capsule OwnerOf(std::unique_ptr<T> object) {
  return py::capsule(object.release(), [](void* pointer) { delete static_cast<T*>(pointer); });
}

std::string ShapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) text += (i ? ", " : "") + std::to_string(array.shape(i));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

py::array AsArray(py::handle object, const std::string& name) {
  try {
    return py::array::ensure(object);
  } catch (const py::error_already_set&) {
  }
  throw Error(name + ": expected a numpy array, got " + std::string(py::str(py::type::of(object))));
}

void RequireRank(const py::array& array, int rank, const std::string& name, const std::string& layout) {
  if (array.ndim() != rank)
    throw Error(name + ": expected a " + std::to_string(rank) + "-D array " + layout + ", got shape " +
                ShapeText(array));
}

// Copies `array` (any layout) into `out` as float32, scaling integer samples to [0, 1].
void CopyAsFloat(const py::array& array, float* out, const std::string& name) {
  const char kind = array.dtype().kind();
  if (kind == 'u' && array.itemsize() == 1) {
    const auto values = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(array);
    std::transform(values.data(), values.data() + values.size(), out, [](std::uint8_t v) { return v / 255.0f; });
  } else if (kind == 'u' && array.itemsize() == 2) {
    const auto values = py::array_t<std::uint16_t, py::array::c_style | py::array::forcecast>::ensure(array);
    std::transform(values.data(), values.data() + values.size(), out, [](std::uint16_t v) { return v / 65535.0f; });
  } else if (kind == 'f') {
    const auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
    std::copy(values.data(), values.data() + values.size(), out);
  } else {
    throw Error(name + ": expected float, uint8 or uint16 samples, got dtype " + std::string(py::str(array.dtype())));
  }
}

}  // namespace

py::array_t<float> FloatArrayOver(float* data, const std::vector<py::ssize_t>& shape, py::handle owner) {
  return py::array_t<float>(shape, ContiguousStrides<float>(shape), data, owner);
}

py::array_t<std::int32_t> LabelArrayOver(std::int32_t* data, const std::vector<py::ssize_t>& shape, py::handle owner) {
  return py::array_t<std::int32_t>(shape, ContiguousStrides<std::int32_t>(shape), data, owner);
}

py::array_t<float> ToArray(DisparityMap map) {
  auto owned = std::make_unique<DisparityMap>(std::move(map));
  const std::vector<py::ssize_t> shape = {owned->height(), owned->width()};
  float* data = owned->data();
  return py::array_t<float>(shape, ContiguousStrides<float>(shape), data, OwnerOf(std::move(owned)));
}

py::array_t<std::int32_t> ToArray(Labels labels) {
  auto owned = std::make_unique<Labels>(std::move(labels));
  const LightFieldShape& s = owned->shape();
  const std::vector<py::ssize_t> shape = {s.nv, s.nu, s.height, s.width};
  std::int32_t* data = owned->data();
  return py::array_t<std::int32_t>(shape, ContiguousStrides<std::int32_t>(shape), data, OwnerOf(std::move(owned)));
}

py::array_t<float> ImageToArray(const cv::Mat& image) {
  if (image.depth() != CV_32F || !image.isContinuous()) throw std::logic_error("ImageToArray: expected a float image");
  auto owned = std::make_unique<cv::Mat>(image);  // shares the buffer, adds a reference
  std::vector<py::ssize_t> shape = {image.rows, image.cols};
  if (image.channels() > 1) shape.push_back(image.channels());
  auto* data = reinterpret_cast<float*>(owned->data);
  return py::array_t<float>(shape, ContiguousStrides<float>(shape), data, OwnerOf(std::move(owned)));
}

DisparityMap DisparityFromArray(py::handle object, const std::string& name) {
  const py::array array = AsArray(object, name);
  RequireRank(array, 2, name, "(H, W)");
  if (array.dtype().kind() != 'f' && array.dtype().kind() != 'i' && array.dtype().kind() != 'u')
    throw Error(name + ": expected real disparities, got dtype " + std::string(py::str(array.dtype())));
  const auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
  DisparityMap map(static_cast<int>(array.shape(1)), static_cast<int>(array.shape(0)));
  std::copy(values.data(), values.data() + values.size(), map.data());
  return map;
}

Labels LabelsFromArray(py::handle object, const std::string& name) {
  const py::array array = AsArray(object, name);
  RequireRank(array, 4, name, "(nv, nu, H, W)");
  if (array.dtype().kind() != 'i' && array.dtype().kind() != 'u')
    throw Error(name + ": expected integer labels, got dtype " + std::string(py::str(array.dtype())));
  const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  LightFieldShape shape;
  shape.nv = static_cast<int>(array.shape(0));
  shape.nu = static_cast<int>(array.shape(1));
  shape.height = static_cast<int>(array.shape(2));
  shape.width = static_cast<int>(array.shape(3));
  Labels labels(shape);
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    const std::int64_t v = values.data()[i];
    if (v < Labels::kUnlabelled || v > INT32_MAX)
      throw Error(name + ": label " + std::to_string(v) + " out of range (-1 = unlabelled, else 0 .. 2^31-1)");
    labels.data()[i] = static_cast<std::int32_t>(v);
  }
  return labels;
}

cv::Mat MaskFromArray(py::handle object, const std::string& name) {
  const py::array array = AsArray(object, name);
  RequireRank(array, 2, name, "(H, W)");
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  cv::Mat mask(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)), CV_8UC1);
  for (py::ssize_t i = 0; i < values.size(); ++i) mask.data[i] = values.data()[i] != 0.0 ? 255 : 0;
  return mask;
}

LightField LightFieldFromArrays(py::handle samples_object, py::handle weights_object) {
  const py::array samples = AsArray(samples_object, "samples");
  RequireRank(samples, 5, "samples", "(nv, nu, H, W, channels)");
  LightFieldShape shape;
  shape.nv = static_cast<int>(samples.shape(0));
  shape.nu = static_cast<int>(samples.shape(1));
  shape.height = static_cast<int>(samples.shape(2));
  shape.width = static_cast<int>(samples.shape(3));
  shape.channels = static_cast<int>(samples.shape(4));
  if (shape.channels != 3) throw Error("samples: expected 3 colour channels (RGB), got shape " + ShapeText(samples));
  if (shape.TotalSamples() == 0) throw Error("samples: the light field is empty, shape " + ShapeText(samples));
  LightField light_field(shape);
  CopyAsFloat(samples, light_field.data(), "samples");
  if (!weights_object.is_none()) {
    const py::array weights = AsArray(weights_object, "weights");
    RequireRank(weights, 4, "weights", "(nv, nu, H, W)");
    for (int axis = 0; axis < 4; ++axis)
      if (weights.shape(axis) != samples.shape(axis))
        throw Error("weights: shape " + ShapeText(weights) + " does not match the samples' " + ShapeText(samples));
    light_field.EnableWeights();
    CopyAsFloat(weights, light_field.weights().data(), "weights");
  }
  RequireFiniteSamples(light_field, "samples");
  return light_field;
}

}  // namespace lfsp::python
