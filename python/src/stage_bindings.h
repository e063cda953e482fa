#pragma once

#include <pybind11/pybind11.h>

namespace lfsp::python {
namespace py = pybind11;

// read, write, decode, grid, depth, segment, evaluate_segmentation, evaluate_depth, recolor, refocus,
// all_in_focus, shear and simulate: each the library call behind the `lfsp` command of that name, on arrays.
void BindStages(py::module_& module);

}  // namespace lfsp::python
