#pragma once

#include <pybind11/pybind11.h>

#include "lfsp/core/hdf5_bundle.h"

namespace lfsp::python {
namespace py = pybind11;

// lfsp.LightField: a light field with what a bundle carries beside it (centre-view disparity, per-ray labels), its
// arrays numpy views over the library's own memory.
void BindLightField(py::module_& module);

// The Python object that owns `bundle` (moved in; nothing is copied).
py::object ToPython(Bundle bundle);

// The light field a stage runs on: the central `views` x `views` of `bundle` as `lfsp` chooses them (0: the
// well-lit ones, ChooseViews). `bundle` itself when that keeps every view; else a cropped copy kept in `storage`.
const Bundle& ChosenViews(const Bundle& bundle, int views, Bundle& storage);

}  // namespace lfsp::python
