// Reading the residual layer's payload (codec/common/residual.h), as
// codec/compress/residual_encoder.h wrote it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "codec/common/residual.h"
#include "codec/common/residual_index.h"

namespace dcurve {

// Decodes one chunk's bytes into q (frames * V * 3 values). plan (may be null) receives the
// chunk's plan with its per-cluster choices. False with a message on malformed bytes; never
// reads outside [bytes, bytes + size).
bool decode_residual_chunk(uint32_t V, const Traversal& trav, const uint8_t* bytes, size_t size, uint32_t frames,
                           int32_t* q, const ResidualOptions& options, ResidualWorkspace* workspace,
                           std::string* error);

// Reverses encode_residuals. `q` receives frame_count * vertex_count * 3 values. Returns
// false with a message on a malformed or corrupted payload (every chunk's CRC is verified);
// never reads outside the payload. `plan`, when not null, receives the complete plan the
// payload was coded with (per-cluster choices and motion maps included).
bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error,
                      const ResidualOptions& options = {}, ResidualPlan* plan = nullptr);

// Reads the predictor tables of model.residual.payload (for reports and tools). The
// per-cluster choices and motion maps live in the coded stream: with `with_clusters` the
// whole payload is decoded to fill them, else they are left empty.
bool decode_predictor_plan(const Model& model, ResidualPlan* plan, std::string* error,
                           const ResidualOptions& options = {}, bool with_clusters = false);

}  // namespace dcurve
