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
// well-lit ones, ChooseViews). `bundle` itself when that keeps every view; else a copy of only the kept views (and
// of labels that have more), in `storage`.
const Bundle& ChosenViews(const Bundle& bundle, int views, Bundle& storage);

// A copy of the central n x n views of `bundle`, its labels cut alike when they have more views; the views left out
// are never copied.
Bundle CentralViewsOf(const Bundle& bundle, int n);

}  // namespace lfsp::python
