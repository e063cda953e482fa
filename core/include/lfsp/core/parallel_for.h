#pragma once

#include <cstddef>
#include <exception>
#include <vector>

namespace lfsp {

// Runs body(i) for every i in [0, count) on all cores (OpenMP, dynamic schedule: items may differ in cost). No
// exception may leave an OpenMP region, so each item's exception is kept and, once every item has run, the one of
// the lowest index is rethrown as it was: the same error on every run, whatever the threads did.
template <typename Body>
void ParallelFor(int count, Body body) {
  if (count <= 0) return;
  std::vector<std::exception_ptr> failure(static_cast<std::size_t>(count));
#pragma omp parallel for schedule(dynamic)
  for (int i = 0; i < count; ++i) {
    try {
      body(i);
    } catch (...) {
      failure[static_cast<std::size_t>(i)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& exception : failure)
    if (exception) std::rethrow_exception(exception);
}

}  // namespace lfsp
