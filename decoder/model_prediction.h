// The motion model's prediction of every input frame on the residual grid: what the
// residual layer's Model predictor subtracts. Encoder and decoder both call this one
// function, so the values are bit-identical on both sides.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

// True when some segment of `model` carries a non-Zero motion.
bool has_motion_model(const Model& model);

// Evaluates the model alone at every frame (frame f at frame coordinate x = f) and rounds
// to the grid of model.residual: out[(f * V + v) * 3 + axis], clamped to +-2^30. Fails when
// the model's tables would exceed `max_floats` or it overflows.
bool model_grid_prediction(const Model& model, uint64_t max_floats, std::vector<int32_t>* out, std::string* error);

}  // namespace dcurve
