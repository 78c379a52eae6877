#include "codec/decompress/residual_decoder.h"

#include "codec/common/bytes.h"
#include "codec/common/crc32.h"
#include "codec/common/error.h"
#include "codec/common/fast_residual.h"
#include "codec/common/int_coder.h"
#include "codec/common/residual_walk.h"
#include "codec/decompress/fast_residual_decoder.h"
#include "codec/decompress/range_decoder.h"
#include "codec/decompress/record_reader.h"

namespace dcurve {
namespace {

using namespace residual_walk;  // what both sides of the format share

// The coder walk_frames drives to read the range-coded stream.
struct StreamReader {
  RangeDecoder dec;
  AdaptiveIntCoder ints{kContexts, kSignContexts};
  SideModels side;
  StreamReader(const uint8_t* data, size_t size) : dec(data, size) {}
  bool residual(int ctx, int sign_ctx, int64_t* r) {
    *r = ints.decode(dec, ctx, sign_ctx);
    return !dec.overrun();
  }
  bool zero_block(int ctx, bool* zero) {
    *zero = dec.decode(side.zero_block[size_t(ctx)]) != 0;
    return !dec.overrun();
  }
  bool index(uint32_t K, uint32_t prev, uint32_t* j) {
    if (dec.decode(side.same)) {
      *j = prev;
      return !dec.overrun();
    }
    uint32_t x = 0;
    for (int b = index_bits(K - 1), node = 1; b > 0; --b) {
      const int bit = dec.decode(side.index_tree[size_t(node)]);
      x = x << 1 | uint32_t(bit);
      node = 2 * node + bit;
    }
    if (x >= K - 1) return false;
    *j = x < prev ? x : x + 1;
    return !dec.overrun();
  }
  bool row(int axis, const MotionRow& prev, MotionRow* row) {
    for (int e = 0; e < 4; ++e) {
      const int64_t value = int64_t(e < 3 ? prev.m[e] : prev.t) + side.params.decode(dec, param_context(e, axis), 0);
      if (value < -kMaxMotionShift || value > kMaxMotionShift) return false;
      (e < 3 ? row->m[e] : row->t) = int32_t(value);
    }
    return motion_row_valid(*row) && !dec.overrun();
  }
};

// Reference frames are written relative to the frame they serve: small numbers.
uint32_t read_ref(RecordReader& r, uint32_t f) {
  int64_t v = 0;
  if (!add_zigzag_delta(int64_t(f), r.varint(), &v)) return UINT32_MAX;
  return v < 0 || v > int64_t(UINT32_MAX) ? UINT32_MAX : uint32_t(v);
}

// Reads a chunk's predictor table into `plan` from the start of its stream.
bool read_plan_table(RecordReader& r, uint32_t frames, const ResidualOptions& options, PredictorPlan* plan,
                     std::string* error) {
  const uint64_t cluster_size = r.varint(), motion_block = r.varint();
  r.end_record();
  if (!r.ok) return fail(error, "residual chunk is truncated");
  if (cluster_size == 0 || cluster_size > UINT32_MAX || motion_block == 0 || motion_block > UINT32_MAX)
    return fail(error, "residual cluster size or motion block is out of range");
  plan->cluster_size = uint32_t(cluster_size);
  plan->motion_block = uint32_t(motion_block);
  plan->order.clear();
  plan->frames.assign(frames, FramePredictors());
  std::vector<uint8_t> decoded(frames, 0);
  uint32_t expect = 0;
  for (uint32_t k = 0; k < frames; ++k) {
    const uint32_t f = read_ref(r, expect);
    if (!r.ok || f >= frames || decoded[f]) return fail(error, "residual frame order is not a permutation of the frames");
    plan->order.push_back(f);
    expect = f + 1;
    const uint8_t count = r.u8();
    if (!r.ok || count == 0 || count > kMaxCandidates) return fail(error, "residual candidate count is out of range");
    plan->frames[f].candidates.resize(count);
    for (auto& candidate : plan->frames[f].candidates)
      for (PredictorChoice& c : candidate) {
        const uint8_t b = r.u8();
        const uint8_t kind = b & 0x0F, spatial = uint8_t(b >> kSpatialShift);
        if (!r.ok || kind >= kPredictorKindCount || spatial >= kSpatialModeCount)
          return fail(error, "residual predictor table is malformed");
        c.kind = PredictorKind(kind);
        c.spatial = SpatialMode(spatial);
        if (has_reference(c.kind)) c.r0 = read_ref(r, f);
        if (c.kind == PredictorKind::Linear) c.r1 = read_ref(r, f);
        if (uses_geometry(c.spatial)) c.g = read_ref(r, f);
        if (!r.ok || !predictor_usable(c, f, decoded, options))
          return fail(error, c.kind == PredictorKind::Model && r.ok
                                 ? "residual stream needs the motion model prediction, which was not supplied"
                                 : "residual predictor table refers to an unavailable frame (not decoded before "
                                   "it in its chunk)");
      }
    if (!geometry_frames_within_bound(plan->frames[f]))
      return fail(error, "residual frame names more than " + std::to_string(kMaxGeometryFrames) + " geometry frames");
    decoded[f] = 1;
    r.end_record();
  }
  return true;
}
}  // namespace

bool decode_residual_chunk(uint32_t V, const Traversal& trav, const uint8_t* bytes, size_t size, uint32_t frames,
                           int32_t* q, const ResidualOptions& options, ResidualWorkspace* ws, std::string* error) {
  ByteReader r(bytes, size);
  const uint32_t checksum = r.u32();
  if (!r.ok) return fail(error, "residual chunk is truncated");
  const size_t stream_size = r.remaining();
  StreamReader coder(r.take(stream_size), stream_size);
  RecordReader table(coder.dec);
  if (!read_plan_table(table, frames, options, &ws->plan, error)) return false;
  const bool ok = walk_frames<true>(V, trav, ws->plan, options, q, coder, *ws);
  if (!ok || !coder.dec.at_clean_end())
    return fail(error, "residual stream is truncated, corrupted or decodes out of range");
  if (kVerifyChecksums && values_checksum(q, size_t(frames) * V * 3) != checksum)
    return fail(error, "residual chunk decodes to other values than were coded (checksum mismatch)");
  return true;
}

namespace {
// The index of model.residual.payload, whose chunks follow it in the payload itself.
bool read_inline_index(const Model& model, ResidualIndex* index, std::string* error) {
  const std::vector<uint8_t>& payload = model.residual.payload;
  if (!read_residual_index(payload.data(), payload.size(), model.meta.frame_count, !model.faces.empty(), UINT64_MAX,
                           index, error))
    return false;
  if (index->data_bytes != payload.size() - index->index_bytes)
    return fail(error, "residual chunk index does not match the payload's chunk data");
  return true;
}

// Decodes every chunk of the payload into q, filling plan (with its per-cluster choices).
bool decode_all(const Model& model, std::vector<int32_t>* q, ResidualPlan* plan, std::string* error,
                const ResidualOptions& options) {
  const uint32_t F = model.meta.frame_count, V = model.meta.vertex_count;
  const size_t stride = size_t(V) * 3, total = stride * F;
  if (options.model_prediction && options.model_prediction->size() != total)
    return fail(error, "model prediction has the wrong number of values");
  const std::vector<uint8_t>& payload = model.residual.payload;
  ResidualIndex index;
  if (!read_inline_index(model, &index, error)) return false;
  const bool fast = index.version == fast_residual::kPayloadVersion;
  Traversal owned;
  const Traversal& trav = fast ? owned : traversal_for(model, options, &owned);
  const FastTraversal derived = fast && !options.fast_traversal ? fast_traversal(model.faces, V) : FastTraversal();
  const FastTraversal& fast_trav = options.fast_traversal ? *options.fast_traversal : derived;
  q->assign(total, 0);
  plan->chunk_frames = index.chunk_frames;
  plan->chunks.assign(index.chunks.size(), PredictorPlan());
  ResidualWorkspace ws;
  for (uint32_t c = 0; c < index.chunks.size(); ++c) {
    const ChunkEntry& e = index.chunks[c];
    const uint8_t* bytes = payload.data() + index.index_bytes + e.offset;
    if (crc32c(bytes, size_t(e.size)) != e.crc && kVerifyChecksums)
      return fail(error, "residual chunk " + std::to_string(c) + " is corrupted (checksum mismatch)");
    const ChunkSpan span = chunk_span(F, index.chunk_frames, c);
    std::vector<int32_t> prediction;
    ResidualOptions chunk_options = options_for_chunk(options, span, stride, &prediction);
    chunk_options.zero_block_flags = has_zero_block_flags(index.version);
    std::string why;
    int32_t* values = q->data() + stride * span.first;
    const bool ok = fast ? decode_fast_chunk(fast_trav, V, bytes, size_t(e.size), span.count,
                                            chunk_options.model_prediction ? chunk_options.model_prediction->data()
                                                                           : nullptr,
                                            values, &why, options.low_rank_basis ? &model.faces : nullptr)
                        : decode_residual_chunk(V, trav, bytes, size_t(e.size), span.count, values, chunk_options,
                                                &ws, &why);
    if (!ok) return fail(error, "residual chunk " + std::to_string(c) + ": " + why);
    plan->chunks[c] = ws.plan;
  }
  return true;
}
}  // namespace

bool decode_predictor_plan(const Model& model, ResidualPlan* plan, std::string* error, const ResidualOptions& options,
                           bool with_clusters) {
  if (with_clusters) {
    std::vector<int32_t> q;
    return decode_all(model, &q, plan, error, options);
  }
  const uint32_t F = model.meta.frame_count;
  const std::vector<uint8_t>& payload = model.residual.payload;
  ResidualIndex index;
  if (!read_inline_index(model, &index, error)) return false;
  plan->chunk_frames = index.chunk_frames;
  plan->chunks.assign(index.chunks.size(), PredictorPlan());
  if (index.version == fast_residual::kPayloadVersion) return true;  // no predictor tables
  for (uint32_t c = 0; c < index.chunks.size(); ++c) {
    const ChunkEntry& e = index.chunks[c];
    if (e.size < 4) return fail(error, "residual chunk is truncated");
    RangeDecoder dec(payload.data() + index.index_bytes + e.offset + 4, size_t(e.size) - 4);  // past the checksum
    RecordReader table(dec);
    if (!read_plan_table(table, chunk_span(F, index.chunk_frames, c).count, options, &plan->chunks[c], error))
      return false;
  }
  return true;
}

bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error, const ResidualOptions& options,
                      ResidualPlan* plan) {
  ResidualPlan own;
  return decode_all(model, q, plan ? plan : &own, error, options);
}

}  // namespace dcurve
