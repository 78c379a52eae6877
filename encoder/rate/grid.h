// The quantization grid that carries the error guarantee: every position rounded to it lies
// within tolerance * L of the input.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"
#include "encoder/io/frames.h"

namespace dcurve {

// Grid step and origin for `anim` at max error `max_distance` (model units, > 0). A cubic
// cell of side s has half-diagonal s*sqrt(3)/2, so s = 2*max_distance/sqrt(3) (shrunk by a
// small margin that absorbs float32 output rounding) is the coarsest grid whose rounding
// stays within the bound; the step is that divided by a fixed refinement (grid.cpp says
// why), or the coarsest when the finer values would not fit an int32. The origin is the
// per-axis minimum over all frames, so grid values start at 0.
ResidualLayer make_grid(const Animation& anim, double max_distance);

// Rounds every frame to the grid: q[(f * V + v) * 3 + axis]. Fails when a value would not fit
// an int32 (a tolerance far too small for the motion's range).
bool quantize_to_grid(const Animation& anim, const ResidualLayer& grid, std::vector<int32_t>* q,
                      std::string* error);

}  // namespace dcurve
