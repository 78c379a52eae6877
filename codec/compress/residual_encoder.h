// Writing the residual layer's payload (codec/common/residual.h);
// codec/decompress/residual_decoder.h reads it back.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "codec/common/residual.h"

namespace dcurve {

// Codes `frames` frames of grid values q (frame-major, V vertices, the chunk's first frame
// first) with `plan` (chunk-local ids, plan_is_valid) into one chunk's bytes; empty for an
// invalid plan. options.model_prediction, when set, holds the chunk's frames only.
std::vector<uint8_t> encode_residual_chunk(uint32_t V, const Traversal& trav, const int32_t* q, uint32_t frames,
                                           const PredictorPlan& plan, const ResidualOptions& options);

// Codes the grid positions `q` (frame_count * vertex_count * 3 values, each an int32) of
// `model` into a payload for model.residual.payload: header, chunk index, chunks. `model`
// supplies counts, faces (the neighbour structure; leave them empty when the file will not
// store them) and curves. Every chunk plan must be plan_is_valid for its frames. An invalid
// plan or mismatched sizes are a caller bug: returns an empty vector.
std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                                      const ResidualOptions& options = {});
// One chunk of every frame with `plan`; null means default_predictor_plan.
std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q,
                                      const PredictorPlan* plan = nullptr, const ResidualOptions& options = {});

// A payload of the given version from its chunks' bytes: header, chunk index, chunk data.
std::vector<uint8_t> assemble_residual_payload(uint8_t version, bool from_faces, uint32_t chunk_frames,
                                               const std::vector<std::vector<uint8_t>>& chunks);

}  // namespace dcurve
