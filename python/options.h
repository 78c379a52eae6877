// The CLI's `dcurve encode` options as Python keyword arguments: the same names with
// underscores (low_rank=8, grid="auto", keep_face_order=True) and the same ranges, each
// checked with a message naming the keyword.
#pragma once
#include <pybind11/pybind11.h>

#include "corpus/input.h"
#include "encoder/encoder.h"

namespace dcurve::python {

struct EncodeSettings {
  EncodeOptions encode;
  InputOptions input;    // encode_file only (and fps, which encode takes too)
  bool force = false;    // encode_file: replace an existing output
  pybind11::object progress = pybind11::none();  // a callable taking the fraction done
};

// Which keywords a function takes: encode's apply to arrays, encode_file's to files.
enum class OptionScope { Arrays, File };

// Applies every keyword of `options` to `settings`; raises TypeError for an unknown keyword
// and dcurve.Error for a value out of its range.
void apply_options(const pybind11::dict& options, OptionScope scope, EncodeSettings* settings);

}  // namespace dcurve::python
