// The fast residual payload (format 4: residual payload version 5, format_spec/residual.md
// section 10): what its encoder (codec/compress/fast_residual_encoder.h) and decoder
// (codec/decompress/fast_residual_decoder.h) must agree on. Built for decode speed: each
// frame has one predictor whose values are a dense loop over the frame (nothing solved per
// frame), and only the non-zero residuals are coded, in vertex-id order, as byte tokens
// through zstd, whose tables are static per stream.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace dcurve {
namespace fast_residual {

constexpr uint8_t kPayloadVersion = 5;

// A frame's predictor: a base kind (bits 0-3) and the spatial flag (bit 4). q1, q2: the
// chunk's frames one and two before; M, M1: the Model prediction of this frame and of the
// one before. With the flag, what is left after the base prediction is predicted again from
// the vertices before it in the fast traversal (codec/common/fast_traversal.h).
enum class FrameKind : uint8_t {
  None = 0,        // 0: with the spatial flag, a frame coded from itself alone
  Previous = 1,    // q1
  Linear = 2,      // 2 q1 - q2
  Model = 3,       // M
  ModelDelta = 4,  // M + q1 - M1: the model plus the previous frame's correction
};
constexpr uint8_t kFrameKindCount = 5;
constexpr uint8_t kSpatialFlag = 0x10;
// With the spatial flag: Mean in place of Parallelogram (codec/common/fast_traversal.h).
constexpr uint8_t kSmoothFlag = 0x20;
// With the spatial flag and base kind None, in a low-rank basis payload only: Fit
// (codec/common/fast_fit.h) in place of the traversal's predictions, weighted by the chunk's
// frame 0 (the mean). Such a frame's values are basis values, within +-kMaxFitValue (LRNK's
// bound) as they are decoded, so the differences Fit weighs fit in int32.
constexpr uint8_t kFitFlag = 0x40;
constexpr int64_t kMaxFitValue = int64_t(1) << 24;
inline FrameKind base_kind(uint8_t kind) { return FrameKind(kind & 0x0f); }
inline bool has_spatial(uint8_t kind) { return (kind & kSpatialFlag) != 0; }
inline bool is_smooth(uint8_t kind) { return (kind & kSmoothFlag) != 0; }
inline bool is_fit(uint8_t kind) { return (kind & kFitFlag) != 0; }

// Frames of the chunk decoded before local frame k that `kind` reads.
inline uint32_t frames_needed(FrameKind kind) {
  switch (kind) {
    case FrameKind::Previous:
    case FrameKind::ModelDelta: return 1;
    case FrameKind::Linear: return 2;
    default: return 0;
  }
}
inline bool uses_model(FrameKind kind) { return kind == FrameKind::Model || kind == FrameKind::ModelDelta; }

// Whether local frame k of a chunk may use the kind byte `kind` (has_model: the file has a
// Model prediction; allow_fit: the payload is a low-rank basis, where Fit may follow frame 0).
inline bool kind_usable(uint8_t kind, uint32_t k, bool has_model, bool allow_fit = false) {
  const FrameKind base = base_kind(kind);
  const bool fit_ok = !is_fit(kind) || (allow_fit && k >= 1 && kind == (kFitFlag | kSpatialFlag));
  return (kind & ~(kFitFlag | kSmoothFlag | kSpatialFlag | 0x0f)) == 0 && (!is_smooth(kind) || has_spatial(kind)) &&
         fit_ok && uint8_t(base) < kFrameKindCount && k >= frames_needed(base) && (has_model || !uses_model(base));
}

// Op bytes: m = b & 7, s = b >> 3. m != 0: skip s vertices, then a vertex whose axes a with
// bit a of m set have non-zero residuals. m = 0: skip 32 (s + 1) vertices.
constexpr uint32_t kLongSkip = 32;
constexpr uint32_t kMaxShortSkip = 31;
// Value bytes: c < 255 is the residual with zigzag(r) = c + 1; 255 is followed by a varint u
// with zigzag(r) = u + 256.
constexpr uint8_t kValueEscape = 255;

// Stream coding byte.
constexpr uint8_t kStreamRaw = 0;
constexpr uint8_t kStreamZstd = 1;

// A base prediction's clamp to int32 (section 10.2).
inline int32_t clamp_int32(int64_t v) { return int32_t(std::clamp<int64_t>(v, INT32_MIN, INT32_MAX)); }

// The base prediction of one frame of n = V * 3 values, clamped to int32 (q1, q2, M, M1 may
// be null when the kind does not read them).
void predict_frame(FrameKind kind, const int32_t* q1, const int32_t* q2, const int32_t* M, const int32_t* M1,
                   size_t n, int32_t* out);

}  // namespace fast_residual
}  // namespace dcurve
