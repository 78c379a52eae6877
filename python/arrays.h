// The encoder's Animation from numpy arrays: frames (F, V, 3), faces (T, 3) and the keywords
// that describe what a renderer draws besides positions (UVs, normals, colours, face groups,
// materials, placement). What encode cannot take is refused with dcurve.Error naming the
// array and the entry.
#pragma once
#include <pybind11/pybind11.h>

#include "encoder/animation.h"

namespace dcurve::python {

// The keywords animation_from_arrays reads (the rest are encode options).
bool is_animation_keyword(const std::string& name);

// Fills `anim` from `frames`, `faces` (None: no connectivity) and the animation keywords of
// `keywords`; frame_rate is left to the caller.
void animation_from_arrays(pybind11::handle frames, pybind11::handle faces, const pybind11::dict& keywords,
                           Animation* anim);

}  // namespace dcurve::python
