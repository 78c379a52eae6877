// A chunked plan cut from a whole-clip plan, so that the chunk choice can measure a chunk
// length by coding it (exact bytes, a pass over the values) instead of planning it again
// (every coding order and cluster layout). Each chunk keeps the whole plan's coding order and
// predictors wherever they reach only frames of the chunk; a predictor that reaches outside
// becomes the spatial-only one (None, or Model where the file has a Model prediction).
#pragma once
#include <cstdint>

#include "codec/common/residual.h"

namespace dcurve {

// `whole` plans all F frames as one chunk; K >= 1. model_prediction: the file has a Model
// prediction to fall back on. The grid values `whole` was planned with stay valid: snapping
// keeps every value within the tolerance whatever predicts it.
ResidualPlan cut_into_chunks(const PredictorPlan& whole, uint32_t F, uint32_t K, bool model_prediction);

}  // namespace dcurve
