#include "python/progress.h"

#include <utility>

namespace py = pybind11;

namespace dcurve::python {

PythonProgress::PythonProgress(py::object callable) : callable_(std::move(callable)) {}

PythonProgress::~PythonProgress() {
  // Destroyed with the GIL held (the binding owns it), so releasing the callable is safe.
  callable_ = py::object();
}

std::function<void(double)> PythonProgress::callback() {
  if (!callable_ || callable_.is_none()) return {};
  return [this](double fraction) { call(fraction); };
}

void PythonProgress::call(double fraction) {
  std::lock_guard<std::mutex> lock(mu_);
  if (failure_) return;
  py::gil_scoped_acquire gil;
  try {
    callable_(fraction);
  } catch (...) {
    failure_ = std::current_exception();
  }
}

void PythonProgress::rethrow() {
  std::exception_ptr failure;
  {
    std::lock_guard<std::mutex> lock(mu_);
    failure = std::exchange(failure_, nullptr);
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace dcurve::python
