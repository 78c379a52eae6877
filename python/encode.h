// dcurve.encode (arrays to bytes) and dcurve.encode_file (what the CLI reads to a .dcrv file):
// the encode runs without the GIL, so other Python threads go on; a progress callable is
// called with the GIL held, one call at a time.
#pragma once
#include <pybind11/pybind11.h>

namespace dcurve::python {

void add_encode_functions(pybind11::module_& m);

}  // namespace dcurve::python
