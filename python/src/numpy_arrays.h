#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "lfsp/core/light_field.h"

namespace lfsp::python {
namespace py = pybind11;

// Arrays over memory that someone else owns: `owner` (a Python object) is kept alive as the array's base, so the
// memory lives as long as any array over it. Nothing is copied.
py::array_t<float> FloatArrayOver(float* data, const std::vector<py::ssize_t>& shape, py::handle owner);
py::array_t<std::int32_t> LabelArrayOver(std::int32_t* data, const std::vector<py::ssize_t>& shape, py::handle owner);

// Arrays that take over a result's memory (moved into a capsule that is the array's base): nothing is copied.
py::array_t<float> ToArray(DisparityMap map);
py::array_t<std::int32_t> ToArray(Labels labels);
py::array_t<float> ImageToArray(const cv::Mat& image);  // float image, H x W (x C); shares the cv::Mat's buffer

// Copies of Python arrays into the library's types, with a one-line lfsp::Error naming `name` for a wrong shape or
// type. Disparities: H x W of any real type. Labels: nv x nu x H x W of any integer type.
DisparityMap DisparityFromArray(py::handle array, const std::string& name);
Labels LabelsFromArray(py::handle array, const std::string& name);
cv::Mat MaskFromArray(py::handle array, const std::string& name);  // H x W, nonzero = inside -> CV_8U 255/0

// A light field from `samples` (nv, nu, H, W, C) and optional `weights` (nv, nu, H, W): always copied into the light
// field's own memory, converted to float32 on the way (uint8 / 255, uint16 / 65535, other reals as they are), from
// any memory layout. NaN or infinite values are refused.
LightField LightFieldFromArrays(py::handle samples, py::handle weights);

}  // namespace lfsp::python
