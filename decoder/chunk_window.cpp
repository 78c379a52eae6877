#include <algorithm>

#include "codec/common/crc32.h"
#include "codec/common/residual_walk.h"
#include "codec/decompress/residual_decoder.h"
#include "decoder_state.h"

namespace dcurve {

size_t SharedState::memory_bytes() const {
  const Model& m = model;
  size_t bytes = sizeof(*this) + m.faces.capacity() * 4 + m.curves.vertices.capacity() * 4 +
                 m.curves.offsets.capacity() * 4 + m.curves.closed.capacity() + m.curves.u.capacity() * 4 +
                 m.residual.payload.capacity() + m.low_rank.coeffs.capacity() * 4 + m.low_rank.poses.capacity() * 4 +
                 m.low_rank.basis_payload.capacity() + index.chunks.capacity() * sizeof(ChunkEntry) +
                 m.render.source.capacity() * 4 + m.render.corners.capacity() * 4 + m.render.face_group.capacity() * 4 +
                 m.materials.json.capacity() + render.memory_bytes();
  for (const MaterialImage& image : m.materials.images) bytes += image.bytes.capacity();
  for (const Segment& s : m.segments) {
    bytes += s.motion.capacity() * sizeof(CurveMotion);
    for (const CurveMotion& cm : s.motion) bytes += cm.coeffs.capacity() * sizeof(float);
  }
  for (const std::vector<uint32_t>* a : {&traversal.order, &traversal.nb_offsets, &traversal.nb, &traversal.para_offsets,
                                          &traversal.para, &traversal.fit_offsets, &traversal.fit})
    bytes += a->capacity() * 4;
  return bytes + fast_traversal.bytes() + predictor.memory_bytes() + (chunks ? chunks->memory_bytes() : 0);
}

ChunkWindow::ChunkWindow(const SharedState& shared) : shared_(shared), rule_(shared.model.meta.inbetween) {}

size_t ChunkWindow::memory_bytes() const {
  size_t stencil = 0;
  for (const StencilSlot& slot : stencil_) stencil += slot.correction.capacity();
  size_t fast = fast_.memory_bytes();
  for (const FrameSlot& s : ring_) fast += s.values.capacity() * sizeof(int32_t);
  for (const FrameSlot& s : model_) fast += s.values.capacity() * sizeof(int32_t);
  return sizeof(*this) + fast + workspace_.bytes() + read_buffer_.capacity() +
         (values_.capacity() + kept_.capacity()) * sizeof(int32_t) +
         (scratch_.capacity() + stencil) * sizeof(float) + prediction_scratch_.bytes();
}

bool ChunkWindow::decode_chunk(uint32_t c, Error* error) {
  const ChunkEntry& e = shared_.index.chunks[c];
  const uint8_t* bytes = shared_.chunks->fetch(e.offset, e.size, &read_buffer_, error);
  if (!bytes) return false;
  if (kVerifyChecksums && crc32c(bytes, size_t(e.size)) != e.crc) {
    if (error) *error = {Status::CorruptChunk, "chunk " + std::to_string(c) + " is corrupted (checksum mismatch)"};
    return false;
  }
  const Model& m = shared_.model;
  const uint32_t V = m.meta.vertex_count;
  const ChunkSpan span = chunk_span(m.meta.frame_count, shared_.index.chunk_frames, c);
  chunk_ = UINT32_MAX;  // until the decode succeeds
  values_.resize(size_t(span.count) * V * 3);
  ChunkModelFrames model_frames(shared_.predictor, span.first, &prediction_scratch_);
  ResidualOptions options;
  options.traversal = &shared_.traversal;
  options.zero_block_flags = residual_walk::has_zero_block_flags(shared_.index.version);
  if (shared_.predictor.active()) options.model_frames = &model_frames;
  std::string why;
  if (!decode_residual_chunk(V, shared_.traversal, bytes, size_t(e.size), span.count, values_.data(), options,
                             &workspace_, &why)) {
    if (error) *error = {Status::CorruptChunk, "chunk " + std::to_string(c) + ": " + why};
    return false;
  }
  chunk_ = c;
  return true;
}

const int32_t* ChunkWindow::frame_values(uint32_t f, Error* error) {
  if (shared_.fast()) return fast_frame_values(f, error);
  const uint32_t K = shared_.index.chunk_frames, c = f / K;
  if (f == kept_frame_ && c != chunk_) return kept_.data();
  if (c != chunk_ && !decode_chunk(c, error)) return nullptr;
  return values_.data() + size_t(f - c * K) * shared_.model.meta.vertex_count * 3;
}

bool ChunkWindow::open_fast_chunk(uint32_t c, Error* error) {
  const ChunkEntry& e = shared_.index.chunks[c];
  fast_chunk_ = UINT32_MAX;  // until the open succeeds
  const uint8_t* bytes = shared_.chunks->fetch(e.offset, e.size, &read_buffer_, error);
  if (!bytes) return false;
  std::string why;
  if (kVerifyChecksums && crc32c(bytes, size_t(e.size)) != e.crc) why = "is corrupted (checksum mismatch)";
  const Model& m = shared_.model;
  const ChunkSpan span = chunk_span(m.meta.frame_count, shared_.index.chunk_frames, c);
  if (why.empty() && !fast_.open(bytes, size_t(e.size), m.meta.vertex_count, span.count, shared_.predictor.active(),
                                  &shared_.fast_traversal, &why))
    why = ": " + why;
  if (!why.empty()) {
    if (error) *error = {Status::CorruptChunk, "chunk " + std::to_string(c) + " " + why};
    return false;
  }
  fast_chunk_ = c;
  return true;
}

// The Model prediction of frame f, kept for the next frame's ModelDelta.
const int32_t* ChunkWindow::model_values(uint32_t f) {
  for (FrameSlot& s : model_)
    if (s.frame == f) return s.values.data();
  FrameSlot& s = model_[0].frame + 1 == f ? model_[1] : model_[0];
  s.values.resize(size_t(shared_.model.meta.vertex_count) * 3);
  shared_.predictor.frame(f, s.values.data(), &prediction_scratch_);
  s.frame = f;
  return s.values.data();
}

// The ring slot frame f is decoded into: its own if the ring holds it (so no frame is held
// twice, and at most two slots, f - 1 and f - 2, are kept), else an empty one, else the
// lowest frame.
ChunkWindow::FrameSlot* ChunkWindow::fast_target(uint32_t f) {
  FrameSlot* target = nullptr;
  for (FrameSlot& s : ring_) {
    if (s.frame == f) return &s;
    const uint32_t back = s.frame < f ? f - s.frame : 0;  // 1, 2: kept, also across a chunk boundary
    if (back == 1 || back == 2) continue;
    if (!target || s.frame == UINT32_MAX || (target->frame != UINT32_MAX && s.frame < target->frame)) target = &s;
  }
  return target;
}

// Decodes the next frame of the open chunk into the ring.
bool ChunkWindow::decode_fast_frame(Error* error) {
  const uint32_t k = fast_.next(), f = fast_chunk_ * shared_.index.chunk_frames + k;
  const int32_t* q[3] = {nullptr, nullptr, nullptr};  // frames f - 1, f - 2
  for (FrameSlot& s : ring_)
    if (s.frame < f && f - s.frame <= 2 && k >= f - s.frame) q[f - s.frame] = s.values.data();
  FrameSlot* target = fast_target(f);
  const fast_residual::FrameKind kind = fast_.kind(k);
  if (!target || (fast_residual::frames_needed(kind) >= 1 && !q[1]) ||
      (fast_residual::frames_needed(kind) >= 2 && !q[2])) {
    fast_chunk_ = UINT32_MAX;  // cannot happen when frames go in order; reopen rather than read a null frame
    if (error) *error = {Status::Internal, "frame " + std::to_string(f) + " lacks the frames before it"};
    return false;
  }
  const bool model = fast_residual::uses_model(kind);
  const int32_t* M1 = model && k >= 1 ? model_values(f - 1) : nullptr;
  const int32_t* M = model ? model_values(f) : nullptr;
  target->frame = UINT32_MAX;
  target->values.resize(size_t(shared_.model.meta.vertex_count) * 3);
  std::string why;
  if (!fast_.decode_frame(q[1], q[2], M, M1, target->values.data(), &why)) {
    fast_chunk_ = UINT32_MAX;
    if (error) *error = {Status::CorruptChunk, "chunk " + std::to_string(f / shared_.index.chunk_frames) + ": " + why};
    return false;
  }
  target->frame = f;
  return true;
}

// Frame f from the ring, else decoded: onwards from the open chunk's next frame when f lies
// ahead of it, else from the start of f's chunk; frames before the last one up to f that
// reads no earlier frame (a Model or None kind: most frames of a low-rank file) are stepped
// over, not decoded, so a seek costs about one frame. A decode keeps the two frames before
// it, so the frame evaluate holds (f - 1 when it asks for f) stays valid.
const int32_t* ChunkWindow::fast_frame_values(uint32_t f, Error* error) {
  for (const FrameSlot& s : ring_)
    if (s.frame == f) return s.values.data();
  const uint32_t K = shared_.index.chunk_frames, c = f / K, local = f - c * K;
  if ((c != fast_chunk_ || fast_.next() > local) && !open_fast_chunk(c, error)) return nullptr;
  uint32_t start = local;
  while (start > fast_.next() && fast_residual::frames_needed(fast_.kind(start)) > 0) --start;
  if (start > fast_.next()) {
    std::string why;
    if (!fast_.skip_frames(start - fast_.next(), &why)) {
      fast_chunk_ = UINT32_MAX;
      if (error) *error = {Status::CorruptChunk, "chunk " + std::to_string(c) + ": " + why};
      return nullptr;
    }
  }
  while (fast_.next() <= local)
    if (!decode_fast_frame(error)) return nullptr;
  for (const FrameSlot& s : ring_)
    if (s.frame == f) return s.values.data();
  return nullptr;  // unreachable: the last frame decoded is f
}

const float* ChunkWindow::stencil_correction(const FrameEvaluator::Place& place, uint32_t f, uint32_t lo,
                                             uint32_t hi, Error* error) {
  for (const StencilSlot& slot : stencil_)
    if (slot.frame == f && slot.span == place.span) return slot.correction.data();
  StencilSlot* free_slot = stencil_;
  for (StencilSlot& slot : stencil_)
    if (slot.frame == UINT32_MAX || slot.frame < lo || slot.frame > hi || slot.span != place.span) {
      free_slot = &slot;
      break;
    }
  const int32_t* values = frame_values(f, error);
  if (!values) return nullptr;
  free_slot->frame = UINT32_MAX;  // until the correction is complete
  free_slot->correction.resize(size_t(shared_.model.meta.vertex_count) * 3);
  shared_.predictor.evaluator().frame_correction(place, shared_.model.residual, values, f, free_slot->correction.data());
  free_slot->frame = f;
  free_slot->span = place.span;
  return free_slot->correction.data();
}

// Frames i - 2 .. i + 3 of the segment with their weights (codec/common/inbetween.h); the
// frames may lie in up to four chunks, which are decoded in frame order, so sequential
// playback still decodes each chunk once.
bool ChunkWindow::evaluate_cubic(const FrameEvaluator::Place& place, float* out, Error* error) {
  const FrameEvaluator& evaluator = shared_.predictor.evaluator();
  const uint32_t first = evaluator.span_first(place), last = evaluator.span_last(place);
  double weight[kInbetweenStencil];
  inbetween_weights(rule_, first, last, place.i, double(place.w), weight);
  const int base = int(place.i) + kInbetweenStencilFirst;
  const uint32_t lo = uint32_t(std::max(base, int(first)));
  const uint32_t hi = std::min(uint32_t(base + kInbetweenStencil - 1), last);
  const float* corrections[kInbetweenStencil] = {};
  for (uint32_t f = lo; f <= hi; ++f) {
    if (weight[f - base] == 0.0) continue;
    corrections[f - base] = stencil_correction(place, f, lo, hi, error);
    if (!corrections[f - base]) return false;
  }
  evaluator.evaluate_weighted(place, corrections, weight, out);
  return true;
}

bool ChunkWindow::evaluate(double x, float* out, Error* error) {
  const FrameEvaluator& evaluator = shared_.predictor.evaluator();
  const FrameEvaluator::Place place = evaluator.locate(x);
  if (!shared_.has_residual()) {
    evaluator.model_at(place, out);
    return true;
  }
  if (rule_ != Inbetween::Linear && place.w != 0.f) return evaluate_cubic(place, out, error);
  const size_t n = size_t(shared_.model.meta.vertex_count) * 3;
  const int32_t* frame = frame_values(place.i, error);
  if (!frame) return false;
  const int32_t* next = nullptr;
  if (place.w != 0.f) {
    const uint32_t K = shared_.index.chunk_frames;
    if (!shared_.fast() && (place.i + 1) % K == 0 && frame != kept_.data()) {
      // Across a chunk boundary: frame i is kept while the next chunk replaces its own.
      kept_.assign(frame, frame + n);
      kept_frame_ = place.i;
      frame = kept_.data();
    }
    next = frame_values(place.i + 1, error);
    if (!next) return false;
  }
  scratch_.resize(n);
  evaluator.evaluate(place, shared_.model.residual, frame, next, scratch_.data(), out);
  return true;
}

}  // namespace dcurve
