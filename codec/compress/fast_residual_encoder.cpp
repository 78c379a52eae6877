#include "codec/compress/fast_residual_encoder.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/residual.h"
#include "codec/common/residual_walk.h"
#include "codec/compress/residual_encoder.h"
#include "codec/compress/zstd_frame_writer.h"
#include "codec/decompress/zstd_frame.h"

namespace dcurve {

using namespace fast_residual;

void fast_frame_residuals(uint8_t kind, const FastTraversal& t, const int32_t* q, const int32_t* q1,
                          const int32_t* q2, const int32_t* M, const int32_t* M1, size_t n, int64_t* r,
                          int32_t* scratch, const FastFit* fit) {
  predict_frame(base_kind(kind), q1, q2, M, M1, n, scratch);
  if (!has_spatial(kind)) {
    for (size_t i = 0; i < n; ++i) r[i] = int64_t(q[i]) - scratch[i];
    return;
  }
  std::vector<int64_t> e(n);  // corrections in traversal order
  for (size_t i = 0; i < n / 3; ++i)
    for (int a = 0; a < 3; ++a) {
      const size_t x = size_t(t.order[i]) * 3 + size_t(a);
      e[i * 3 + size_t(a)] = int64_t(q[x]) - scratch[x];
    }
  for (size_t i = 0; i < n / 3; ++i) {
    int64_t p[3];
    if (is_fit(kind)) fast_fit_position(*fit, i, e.data(), p);
    else
      for (int a = 0; a < 3; ++a) p[a] = fast_spatial(t, i, e.data(), a, is_smooth(kind));
    for (int a = 0; a < 3; ++a) r[i * 3 + size_t(a)] = e[i * 3 + size_t(a)] - p[a];
  }
}

namespace {
void append_value(int64_t r, ByteWriter* values) {
  const uint64_t z = zigzag_encode(r);
  if (z - 1 < kValueEscape) {
    values->u8(uint8_t(z - 1));
    return;
  }
  values->u8(kValueEscape);
  values->varint(z - 256);
}
}  // namespace

uint32_t append_frame_tokens(const int64_t* r, uint32_t V, ByteWriter* ops, ByteWriter* values) {
  uint32_t count = 0, cursor = 0;
  for (uint32_t v = 0; v < V; ++v) {
    const int64_t* x = r + size_t(v) * 3;
    const uint8_t mask = uint8_t((x[0] != 0) | (x[1] != 0) << 1 | (x[2] != 0) << 2);
    if (mask == 0) continue;
    uint32_t gap = v - cursor;
    while (gap > kMaxShortSkip) {
      const uint32_t s = std::min<uint32_t>(gap / kLongSkip, kMaxShortSkip + 1) - 1;
      ops->u8(uint8_t(s << 3));
      gap -= kLongSkip * (s + 1);
      ++count;
    }
    ops->u8(uint8_t(gap << 3 | mask));
    ++count;
    for (int a = 0; a < 3; ++a)
      if (x[a] != 0) append_value(x[a], values);
    cursor = v + 1;
  }
  return count;
}

namespace {
// A stream as its coding byte, sizes and bytes: zstd when that is smaller and within the
// expansion the reader accepts.
void write_stream(const std::vector<uint8_t>& raw, ByteWriter* w) {
  const std::vector<uint8_t> packed = zstd_frame(raw, 19);
  if (!packed.empty() && packed.size() + 2 < raw.size() && zstd_size_plausible(raw.size(), packed.size())) {
    w->u8(kStreamZstd);
    w->varint(raw.size());
    w->varint(packed.size());
    w->bytes(packed.data(), packed.size());
    return;
  }
  w->u8(kStreamRaw);
  w->varint(raw.size());
  w->bytes(raw.data(), raw.size());
}
}  // namespace

std::vector<uint8_t> encode_fast_chunk(const FastTraversal& t, uint32_t V, const uint8_t* kinds, uint32_t frames,
                                       const int32_t* q, const int32_t* model, const FastFit* fit) {
  const size_t n = size_t(V) * 3;
  std::vector<int64_t> r(n);
  std::vector<int32_t> scratch(n);
  ByteWriter ops, values;
  std::vector<uint32_t> op_counts, checksums;
  for (uint32_t k = 0; k < frames; ++k) {
    if (!kind_usable(kinds[k], k, model != nullptr, fit != nullptr)) return {};
    const int32_t* f = q + k * n;
    fast_frame_residuals(kinds[k], t, f, k >= 1 ? f - n : nullptr, k >= 2 ? f - 2 * n : nullptr,
                         model ? model + k * n : nullptr, model && k >= 1 ? model + (k - 1) * n : nullptr, n,
                         r.data(), scratch.data(), fit);
    op_counts.push_back(append_frame_tokens(r.data(), V, &ops, &values));
    checksums.push_back(residual_walk::values_checksum(f, n));
  }
  ByteWriter w;
  w.bytes(kinds, frames);
  for (uint32_t c : op_counts) w.varint(c);
  for (uint32_t c : checksums) w.u32(c);
  write_stream(ops.data(), &w);
  write_stream(values.data(), &w);
  return std::move(w.data());
}

std::vector<uint8_t> encode_fast_residuals(const Model& model, const std::vector<int32_t>& q,
                                           const std::vector<uint8_t>& kinds, uint32_t chunk_frames,
                                           const std::vector<int32_t>* model_prediction) {
  const uint32_t F = model.meta.frame_count, V = model.meta.vertex_count;
  const size_t n = size_t(V) * 3;
  if (chunk_frames == 0 || q.size() != n * F || kinds.size() != F ||
      (model_prediction && model_prediction->size() != q.size()))
    return {};
  const FastTraversal t = fast_traversal(model.faces, V);
  std::vector<std::vector<uint8_t>> chunks;
  for (uint32_t c = 0; c < chunk_count(F, chunk_frames); ++c) {
    const ChunkSpan span = chunk_span(F, chunk_frames, c);
    const uint8_t* chunk_kinds = kinds.data() + span.first;
    const bool uses_fit = std::any_of(chunk_kinds, chunk_kinds + span.count, is_fit);
    const FastFit fit = uses_fit ? fast_fit(model.faces, t, q.data() + n * span.first) : FastFit();
    chunks.push_back(encode_fast_chunk(t, V, chunk_kinds, span.count, q.data() + n * span.first,
                                       model_prediction ? model_prediction->data() + n * span.first : nullptr,
                                       uses_fit ? &fit : nullptr));
    if (chunks.back().empty()) return {};
  }
  return assemble_residual_payload(kPayloadVersion, !model.faces.empty(), chunk_frames, chunks);
}

}  // namespace dcurve
