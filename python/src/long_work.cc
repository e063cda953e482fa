#include "long_work.h"

#include <memory>
#include <string>

namespace lfsp::python {
namespace {

void OnInterrupt(int) { RequestCancellation(); }

bool OnMainThread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

}  // namespace

InterruptibleScope::InterruptibleScope() {
  if (!OnMainThread()) return;
  struct sigaction action {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  installed_ = sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptibleScope::~InterruptibleScope() {
  if (installed_) sigaction(SIGINT, &previous_, nullptr);
}

void BindProgress(py::module_& module) {
  module.def(
      "set_progress",
      [](py::object callback) {
        if (callback.is_none()) {
          Progress::SetObserver({});
          return;
        }
        // Shared so that the observer can be copied; deleted under the GIL when the observer is replaced.
        auto function = std::shared_ptr<py::object>(new py::object(std::move(callback)), [](py::object* object) {
          const py::gil_scoped_acquire gil;
          delete object;
        });
        Progress::SetObserver([function](const std::string& label, std::size_t done, std::size_t total) {
          const py::gil_scoped_acquire gil;
          (*function)(label, done, total);  // an exception it raises stops the work and reaches the caller
        });
      },
      py::arg("callback"),
      "set_progress(callback)\n\nCalls callback(label, done, total) at every progress step of long work (decode, "
      "depth, segment, "
      "evaluate); None restores the default (the command line's progress bar, on a terminal only).");
}

}  // namespace lfsp::python
