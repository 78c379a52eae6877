// dcurve.Decoder: the runtime decoder (decoder/dcurve.hpp) over bytes or a path, its frames
// as float32 numpy arrays and what the file stores besides them (render vertices and their
// attributes, face groups, materials, placement).
#pragma once
#include <pybind11/pybind11.h>

namespace dcurve::python {

void add_decoder_class(pybind11::module_& m);

}  // namespace dcurve::python
