#pragma once

#include <pybind11/pybind11.h>

#include <csignal>
#include <utility>

#include "lfsp/core/progress.h"

namespace lfsp::python {
namespace py = pybind11;

// While it lives, Ctrl-C asks the library to stop (RequestCancellation) instead of waiting for Python to see it:
// Python runs its own SIGINT handler only between bytecodes, which never come while C++ works without the GIL. Only
// on the main thread, where Python itself handles signals; the previous handler is restored afterwards.
class InterruptibleScope {
 public:
  InterruptibleScope();
  ~InterruptibleScope();
  InterruptibleScope(const InterruptibleScope&) = delete;
  InterruptibleScope& operator=(const InterruptibleScope&) = delete;

 private:
  bool installed_ = false;
  struct sigaction previous_ {};
};

// Runs long library work with the GIL released and Ctrl-C turned into lfsp::Cancelled at the work's next progress
// tick (the module translates it into KeyboardInterrupt).
template <typename Work>
auto RunLongWork(Work&& work) {
  ClearCancellation();
  const InterruptibleScope interruptible;
  const py::gil_scoped_release release;
  return std::forward<Work>(work)();
}

// lfsp.set_progress(callback): callback(label, done, total) at every progress step of long work; None = the
// command line's display on a terminal only.
void BindProgress(py::module_& module);

}  // namespace lfsp::python
