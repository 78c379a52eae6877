// The residual layer: integer grid positions of every input frame, coded against
// predictions chosen per frame and axis, with a context-adaptive range coder. Encoder and
// decoder share this file so the round trip is bit-exact. format_spec/residual.md is the
// byte layout.
//
// Grid positions are laid out frame-major: q[(f * V + v) * 3 + axis].
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"
#include "codec/predictors.h"

namespace dcurve {

// How frames are coded: in which order, each axis with which predictor.
struct PredictorPlan {
  std::vector<uint32_t> order;           // a permutation of [0, frame_count): coding order
  std::vector<PredictorChoice> choices;  // entry f * 3 + axis (indexed by frame, not position)
};

// The plan used when the caller has none: time order, frame 0 from its mesh neighbours,
// every later frame as the previous frame plus the neighbours' motion.
PredictorPlan default_predictor_plan(uint32_t frame_count);

// Whether `plan` fits frame_count and every choice refers only to frames coded before it.
bool plan_is_valid(const PredictorPlan& plan, uint32_t frame_count, const ResidualOptions& options);

// Codes the grid positions `q` (frame_count * vertex_count * 3 values, each an int32) of
// `model` into a payload for model.residual.payload. `model` supplies counts, faces (the
// neighbour structure; leave them empty when the file will not store them) and curves.
// `plan` (plan_is_valid) picks the order and predictors; null means default_predictor_plan.
// An invalid plan or mismatched sizes are a caller bug: returns an empty vector.
std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q,
                                      const PredictorPlan* plan = nullptr,
                                      const ResidualOptions& options = {});

// Reverses encode_residuals. `q` receives frame_count * vertex_count * 3 values. Returns
// false with a message on a malformed or corrupted payload (a checksum of the decoded
// values is verified); never reads outside the payload.
bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error,
                      const ResidualOptions& options = {});

// Reads only the predictor table of model.residual.payload (for reports and tools).
bool decode_predictor_plan(const Model& model, PredictorPlan* plan, std::string* error,
                           const ResidualOptions& options = {});

// Grid value -> model units, exactly as the decoder converts it (float32 output).
inline float grid_to_model(const ResidualLayer& layer, int axis, int64_t value) {
  return float(layer.origin[axis] + layer.step * double(value));
}

// The residuals encode_residuals would code, in coding order (frame in plan order,
// traversal position, axis): for measuring the entropy coder against general-purpose compressors.
std::vector<int64_t> residual_values(const Model& model, const std::vector<int32_t>& q, const PredictorPlan& plan,
                                     const ResidualOptions& options = {});

}  // namespace dcurve
