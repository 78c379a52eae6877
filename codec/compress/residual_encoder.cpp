#include "codec/compress/residual_encoder.h"

#include "codec/common/bytes.h"
#include "codec/common/crc32.h"
#include "codec/common/int_coder.h"
#include "codec/common/residual_walk.h"
#include "codec/compress/range_encoder.h"
#include "codec/compress/record_writer.h"

namespace dcurve {
namespace {

using namespace residual_walk;  // what both sides of the format share

// The coder walk_frames drives to write the range-coded stream.
struct StreamWriter {
  RangeEncoder enc;
  AdaptiveIntCoder ints{kContexts, kSignContexts};
  SideModels side;
  bool residual(int ctx, int sign_ctx, int64_t* r) {
    ints.encode(enc, ctx, sign_ctx, *r);
    return true;
  }
  bool zero_block(int ctx, bool* zero) {
    enc.encode(side.zero_block[size_t(ctx)], *zero ? 1 : 0);
    return true;
  }
  bool index(uint32_t K, uint32_t prev, uint32_t* j) {
    enc.encode(side.same, *j == prev);
    if (*j == prev) return true;
    const uint32_t x = *j < prev ? *j : *j - 1;
    const int bits = index_bits(K - 1);
    for (int b = bits - 1, node = 1; b >= 0; --b) {
      const int bit = int(x >> b & 1);
      enc.encode(side.index_tree[size_t(node)], bit);
      node = 2 * node + bit;
    }
    return true;
  }
  bool row(int axis, const MotionRow& prev, MotionRow* row) {
    for (int e = 0; e < 4; ++e) {
      const int32_t value = e < 3 ? row->m[e] : row->t, before = e < 3 ? prev.m[e] : prev.t;
      side.params.encode(enc, param_context(e, axis), 0, int64_t(value) - before);
    }
    return true;
  }
};

// Reference frames are written relative to the frame they serve: small numbers.
void write_ref(ByteWriter& w, uint32_t f, uint32_t r) { w.varint(zigzag_encode(int64_t(r) - int64_t(f))); }

// The predictor table as records (format_spec/residual.md, "Chunk"): cluster size and
// motion block, then one record per frame in coding order.
void write_plan_table(const PredictorPlan& plan, RecordWriter& out) {
  ByteWriter w;
  w.varint(plan.cluster_size);
  w.varint(plan.motion_block);
  out.record(w.data());
  uint32_t expect = 0;  // time order costs one byte per frame: delta to the expected frame
  for (uint32_t f : plan.order) {
    ByteWriter r;
    write_ref(r, expect, f);
    expect = f + 1;
    r.u8(uint8_t(plan.frames[f].candidates.size()));
    for (const auto& candidate : plan.frames[f].candidates)
      for (const PredictorChoice& c : candidate) {
        r.u8(uint8_t(uint8_t(c.kind) | uint8_t(c.spatial) << kSpatialShift));
        if (has_reference(c.kind)) write_ref(r, f, c.r0);
        if (c.kind == PredictorKind::Linear) write_ref(r, f, c.r1);
        if (uses_geometry(c.spatial)) write_ref(r, f, c.g);
      }
    out.record(r.data());
  }
}
}  // namespace

std::vector<uint8_t> encode_residual_chunk(uint32_t V, const Traversal& trav, const int32_t* q, uint32_t frames,
                                           const PredictorPlan& plan, const ResidualOptions& options) {
  if (!plan_is_valid(plan, frames, V, options)) return {};
  StreamWriter coder;
  RecordWriter table(coder.enc);
  write_plan_table(plan, table);
  ResidualWorkspace ws;
  PredictorPlan p = plan;
  std::vector<int32_t> work(q, q + size_t(frames) * V * 3);  // the walker takes a mutable pointer
  walk_frames<false>(V, trav, p, options, work.data(), coder, ws);
  const std::vector<uint8_t>& stream = coder.enc.finish();
  ByteWriter w;
  w.u32(values_checksum(q, size_t(frames) * V * 3));
  w.bytes(stream.data(), stream.size());
  return std::move(w.data());
}

std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                                      const ResidualOptions& options) {
  const uint32_t F = model.meta.frame_count, V = model.meta.vertex_count, K = plan.chunk_frames;
  const size_t stride = size_t(V) * 3;
  if (K == 0 || plan.chunks.size() != chunk_count(F, K) || q.size() != stride * F ||
      (options.model_prediction && options.model_prediction->size() != q.size()))
    return {};
  Traversal owned;
  const Traversal& trav = traversal_for(model, options, &owned);
  std::vector<std::vector<uint8_t>> chunks;
  for (uint32_t c = 0; c < plan.chunks.size(); ++c) {
    const ChunkSpan span = chunk_span(F, K, c);
    std::vector<int32_t> prediction;
    const ResidualOptions chunk_options = options_for_chunk(options, span, stride, &prediction);
    chunks.push_back(
        encode_residual_chunk(V, trav, q.data() + stride * span.first, span.count, plan.chunks[c], chunk_options));
    if (chunks.back().empty()) return {};
  }
  return assemble_residual_payload(options.zero_block_flags ? kFormatVersion : kOldestFormatVersion, trav.from_faces,
                                   K, chunks);
}

std::vector<uint8_t> assemble_residual_payload(uint8_t version, bool from_faces, uint32_t chunk_frames,
                                               const std::vector<std::vector<uint8_t>>& chunks) {
  ByteWriter w;
  w.u8(version);
  w.u8(from_faces ? 1 : 0);
  w.varint(chunk_frames);
  w.varint(chunks.size());
  uint64_t offset = 0;
  for (const std::vector<uint8_t>& bytes : chunks) {
    w.varint(offset);
    w.varint(bytes.size());
    w.u32(crc32c(bytes.data(), bytes.size()));
    offset += bytes.size();
  }
  for (const std::vector<uint8_t>& bytes : chunks) w.bytes(bytes.data(), bytes.size());
  return std::move(w.data());
}

std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q, const PredictorPlan* plan,
                                      const ResidualOptions& options) {
  return encode_residuals(model, q, single_chunk_plan(plan ? *plan : default_predictor_plan(model.meta.frame_count)),
                          options);
}

}  // namespace dcurve
