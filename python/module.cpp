// The Python module `dcurve`: encode numpy arrays or files the CLI reads, decode .dcrv files.
#include <pybind11/pybind11.h>

#include "dcurve.h"
#include "python/decoder.h"
#include "python/encode.h"
#include "python/error.h"

namespace py = pybind11;

PYBIND11_MODULE(dcurve, m) {
  m.doc() = "dcurve: compress animated triangle meshes into .dcrv files within a max error, and decode them.";
  py::register_exception<dcurve::python::Error>(m, "Error", PyExc_ValueError);
  dcurve::python::add_encode_functions(m);
  dcurve::python::add_decoder_class(m);
  m.attr("__version__") = std::to_string(DCURVE_VERSION_MAJOR) + "." + std::to_string(DCURVE_VERSION_MINOR) + "." +
                          std::to_string(DCURVE_VERSION_PATCH);
}
