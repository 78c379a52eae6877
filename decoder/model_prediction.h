// The Model predictor's values for every input frame on the residual grid: what the
// residual layer's Model predictor subtracts. They come from the file's low-rank model
// (LRNK) when it has one, else from its PDE motion model. Encoder and decoder both call
// this one function, so the values are bit-identical on both sides.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

// True when some segment of `model` carries a non-Zero motion.
bool has_motion_model(const Model& model);

// True when the residual layer of `model` may use the Model predictor: the file has a
// low-rank model or a PDE motion model (validate_model forbids both at once).
bool has_model_prediction(const Model& model);

// The Model predictor of every frame, grid units of model.residual:
// out[(f * V + v) * 3 + axis], clamped to +-2^30. Low-rank: decodes the mean and basis
// (format_spec/dcrv.md section 17) and evaluates them in integer arithmetic. PDE: evaluates
// the model alone at frame coordinate x = f and rounds to the grid. Fails when the tables
// would exceed `max_floats` values, the low-rank basis does not decode or is out of range.
bool model_grid_prediction(const Model& model, uint64_t max_floats, std::vector<int32_t>* out, std::string* error);

}  // namespace dcurve
