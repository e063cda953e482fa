// The extension module `lfsp._lfsp`: the stage layer on numpy arrays. The package `lfsp` (python/lfsp) re-exports
// it with a few pure-Python conveniences.

#include <pybind11/pybind11.h>
#include <spdlog/spdlog.h>

#include <new>

#include "lfsp/core/error.h"
#include "lfsp/core/progress.h"
#include "lfsp/core/version.h"
#include "light_field_binding.h"
#include "long_work.h"
#include "stage_bindings.h"

namespace py = pybind11;

namespace {

// Python code prints its own messages; the library's log (the command line's info lines) shows warnings only
// unless asked.
void BindLogging(py::module_& module) {
  spdlog::set_pattern("lfsp: %v");
  spdlog::set_level(spdlog::level::warn);
  module.def(
      "set_log_level",
      [](const std::string& level) {
        const spdlog::level::level_enum value = spdlog::level::from_str(level);
        if (value == spdlog::level::off && level != "off")
          throw lfsp::Error("set_log_level: unknown level '" + level + "' (debug, info, warning, error, off)");
        spdlog::set_level(value);
      },
      py::arg("level"),
      "set_log_level(level)\n\nThe library's log level: debug, info, warning (the default), error or off.");
}

}  // namespace

PYBIND11_MODULE(_lfsp, module) {
  module.doc() = "lfsp on numpy arrays (see the package lfsp)";
  module.attr("__version__") = lfsp::Version();  // the same string as `lfsp --version` and every summary
  // Every docstring starts with its own signature, in the keywords' terms (pybind11's would say **kwargs).
  py::options options;
  options.disable_function_signatures();
  // lfsp.Error: bad input (a file that is missing, truncated or wrong, an option out of range), with the command
  // line's one-line message. A ValueError, so code that catches those catches it.
  static py::exception<lfsp::Error> error(module, "Error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const lfsp::Error& e) {
      error(e.what());
    } catch (const lfsp::Cancelled&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
  BindLogging(module);
  lfsp::python::BindProgress(module);
  lfsp::python::BindLightField(module);
  lfsp::python::BindStages(module);
}
