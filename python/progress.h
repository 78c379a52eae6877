// A Python progress callable as the encoder's progress callback: called from the encoder's
// threads with the GIL taken for the call only. An exception it raises stops further calls
// and is raised again once the encode returns (the encode itself cannot be cut short).
#pragma once
#include <pybind11/pybind11.h>

#include <exception>
#include <functional>
#include <memory>
#include <mutex>

namespace dcurve::python {

class PythonProgress {
 public:
  explicit PythonProgress(pybind11::object callable);
  ~PythonProgress();
  // The callback for EncodeOptions::progress (empty without a callable); valid while this lives.
  std::function<void(double)> callback();
  // With the GIL held: raises what the callable raised, if it did.
  void rethrow();

 private:
  void call(double fraction);

  pybind11::object callable_;
  std::mutex mu_;
  std::exception_ptr failure_;
};

}  // namespace dcurve::python
