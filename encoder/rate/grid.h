// The quantization grid that carries the error guarantee: every position rounded to it lies
// within tolerance * L of the input.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"
#include "encoder/io/frames.h"

namespace dcurve {

// Grid step and origin for `anim` at max error `max_distance` (model units, > 0): the
// coarsest grid whose rounding stays within the bound (cube side 2 * max_distance /
// sqrt(3), less a margin for float32 output rounding) made `refinement` (>= 1) times finer,
// or the coarsest when the finer values would not fit an int32. The origin is the per-axis
// minimum over all frames, so grid values start at 0.
ResidualLayer make_grid(const Animation& anim, double max_distance, double refinement = 1.0);

// The coarsest grid or a finer one (grid.cpp says why), whichever codes `anim` (or, when
// it is large, a run of frames from its middle) smaller with the residual layer alone.
// `model` supplies counts, faces and curves, as the residual layer will see them.
// threads: 0 = all cores; the choice never depends on it. Costs two residual encodes with
// one coding order and no clusters.
ResidualLayer choose_grid(const Model& model, const Animation& anim, double max_distance, int threads);

// Rounds every frame to the grid: q[(f * V + v) * 3 + axis]. Fails when a value would not fit
// an int32 (a tolerance far too small for the motion's range).
bool quantize_to_grid(const Animation& anim, const ResidualLayer& grid, std::vector<int32_t>* q,
                      std::string* error);

}  // namespace dcurve
