// Writing the fast residual payload (format 4, format_spec/residual.md section 10);
// codec/decompress/fast_residual_decoder.h reads it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/bytes.h"
#include "codec/common/fast_fit.h"
#include "codec/common/fast_residual.h"
#include "codec/common/fast_traversal.h"
#include "codec/common/model.h"

namespace dcurve {

// The residuals r (n = V * 3 values) of frame q against the kind byte `kind`'s prediction
// from q1, q2 (the frames before it), M and M1 (the Model prediction of this frame and the one
// before): what the decoder adds back, by vertex id, or with the spatial flag by position of
// t. scratch: n values. fit: the chunk's Fit weights, read by a kind with the Fit flag.
void fast_frame_residuals(uint8_t kind, const FastTraversal& t, const int32_t* q, const int32_t* q1,
                          const int32_t* q2, const int32_t* M, const int32_t* M1, size_t n, int64_t* r,
                          int32_t* scratch, const FastFit* fit = nullptr);

// Appends one frame's residuals (V * 3, in the order they are coded) as op and value bytes;
// returns the op count.
uint32_t append_frame_tokens(const int64_t* r, uint32_t V, ByteWriter* ops, ByteWriter* values);

// One chunk's bytes: `frames` frames of grid values q (frame-major) coded with kinds[k]
// (kind_usable for each), model the chunk's Model prediction (frames * V * 3) or null, t
// fast_traversal of the file's faces; fit: fast_fit of the chunk's frame 0, which allows
// kinds with the Fit flag (a low-rank basis payload), or null.
std::vector<uint8_t> encode_fast_chunk(const FastTraversal& t, uint32_t V, const uint8_t* kinds, uint32_t frames,
                                       const int32_t* q, const int32_t* model, const FastFit* fit = nullptr);

// The payload of model's residual layer: q (frame_count * V * 3 grid values) in chunks of
// chunk_frames, frame f coded with kinds[f]; model_prediction: every frame's Model
// prediction, or null when the file has none. Empty when a kind cannot code its frame.
// Kinds with the Fit flag (a low-rank basis) are weighted by each chunk's frame 0.
std::vector<uint8_t> encode_fast_residuals(const Model& model, const std::vector<int32_t>& q,
                                           const std::vector<uint8_t>& kinds, uint32_t chunk_frames,
                                           const std::vector<int32_t>* model_prediction);

}  // namespace dcurve
