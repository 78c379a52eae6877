#include "codec/residual.h"

#include <algorithm>

#include "codec/bytes.h"
#include "codec/crc32.h"
#include "codec/error.h"
#include "codec/int_coder.h"
#include "codec/range_coder.h"

namespace dcurve {
namespace {

constexpr uint8_t kFormatVersion = 1;
// A plan entry byte: predictor kind in bits 0-3, spatial mode in bits 4-5.
constexpr int kSpatialShift = 4;

// Context of a residual: how large the residuals around it already were. Neighbours in
// this frame (7 classes, the last one for "no decoded neighbour"), the same vertex and
// axis in the temporal source frame (4), the earlier axes of the same vertex in this
// frame (4, plus 1 for the first axis). The temporal source is the base prediction's
// first reference frame, else the frame coded just before.
constexpr int kNeighbourClasses = 7, kTemporalClasses = 4, kAxisClasses = 5;
constexpr int kContexts = kNeighbourClasses * kTemporalClasses * kAxisClasses;
// Sign context: signs (-, 0, +) of the temporal source's residual and of the sum of the
// decoded neighbours' residuals: drift out of the tolerance ball repeats its direction.
constexpr int kSignContexts = 9;

int magnitude_class(uint32_t m) {
  return m < 3 ? int(m) : m <= 4 ? 3 : m <= 8 ? 4 : 5;
}

int sign3(int64_t v) { return v < 0 ? 0 : v == 0 ? 1 : 2; }

// Residuals are kept, clamped to a byte, for the contexts of later vertices and frames.
int8_t clamp8(int64_t r) { return int8_t(r < -127 ? -127 : r > 127 ? 127 : r); }

// Walks the frames in decoding order, calling step(ctx, &r) for every residual r. When
// decoding, step writes r and the walker fills q; otherwise the walker computes r from q
// and step codes or records it. One body for all uses so they cannot drift apart.
template <bool kDecode, class Step>
bool walk_frames(const Model& model, const Traversal& trav, const PredictorPlan& plan,
                 const ResidualOptions& options, int32_t* q, Step step) {
  const uint32_t V = model.meta.vertex_count;
  const size_t stride = size_t(V) * 3;
  std::vector<int64_t> base(stride);
  std::vector<int8_t> res(stride * plan.order.size(), 0);
  const int8_t* previous = nullptr;  // residuals of the frame coded last
  for (uint32_t f : plan.order) {
    const PredictorChoice* choice = &plan.choices[size_t(f) * 3];
    for (int a = 0; a < 3; ++a) base_prediction(choice[a], f, a, V, q, options, &base[size_t(a) * V]);
    int32_t* qf = q + size_t(f) * stride;
    int8_t* rf = &res[size_t(f) * stride];
    const int8_t* source[3];
    for (int a = 0; a < 3; ++a) {
      const PredictorChoice& c = choice[a];
      const bool has_ref = c.kind == PredictorKind::Reference || c.kind == PredictorKind::Linear;
      source[a] = has_ref ? &res[size_t(c.r0) * stride] : previous;
    }
    for (uint32_t pos = 0; pos < V; ++pos) {
      const uint32_t v = trav.order[pos];
      const uint32_t nb_begin = trav.nb_offsets[pos], nb_end = trav.nb_offsets[pos + 1];
      uint32_t axis_max = 0;
      int64_t preds[3];
      vertex_prediction(choice, trav, pos, V, qf, base.data(), preds);
      for (int a = 0; a < 3; ++a) {
        const int64_t pred = preds[a];
        int nb_class = kNeighbourClasses - 1;
        int nb_sum = 0;
        if (nb_begin != nb_end) {
          uint32_t sum = 0;
          for (uint32_t k = nb_begin; k < nb_end; ++k) {
            const int n = rf[size_t(trav.nb[k]) * 3 + size_t(a)];
            sum += uint32_t(n < 0 ? -n : n);
            nb_sum += n;
          }
          nb_class = magnitude_class((sum + (nb_end - nb_begin) - 1) / (nb_end - nb_begin));
        }
        const size_t i = size_t(v) * 3 + size_t(a);
        const int t = source[a] ? source[a][i] : 0;
        const int t_class = std::min(magnitude_class(uint32_t(t < 0 ? -t : t)), kTemporalClasses - 1);
        const int a_class = a == 0 ? kAxisClasses - 1 : std::min(magnitude_class(axis_max), kAxisClasses - 2);
        const int ctx = (nb_class * kTemporalClasses + t_class) * kAxisClasses + a_class;
        const int sign_ctx = sign3(t) * 3 + sign3(nb_sum);
        int64_t r;
        if constexpr (kDecode) {
          if (!step(ctx, sign_ctx, &r)) return false;
          const int64_t value = pred + r;
          if (value < INT32_MIN || value > INT32_MAX) return false;
          qf[i] = int32_t(value);
        } else {
          r = int64_t(qf[i]) - pred;
          step(ctx, sign_ctx, &r);
        }
        rf[i] = clamp8(r);
        axis_max = std::max(axis_max, uint32_t(rf[i] < 0 ? -rf[i] : rf[i]));
      }
    }
    previous = rf;
  }
  return true;
}

// CRC-32C of the values as little-endian int32, so a corrupted stream that still decodes
// to in-range values is caught.
uint32_t values_checksum(const std::vector<int32_t>& q) {
  uint32_t crc = 0;
  uint8_t chunk[4096];
  for (size_t i = 0; i < q.size();) {
    size_t n = 0;
    for (; n + 4 <= sizeof chunk && i < q.size(); ++i, n += 4) {
      const uint32_t u = uint32_t(q[i]);
      for (int b = 0; b < 4; ++b) chunk[n + size_t(b)] = uint8_t(u >> (8 * b));
    }
    crc = crc32c(chunk, n, crc);
  }
  return crc;
}

}  // namespace

PredictorPlan default_predictor_plan(uint32_t frame_count) {
  PredictorPlan plan;
  plan.choices.resize(size_t(frame_count) * 3);
  for (uint32_t f = 0; f < frame_count; ++f) {
    plan.order.push_back(f);
    for (int a = 0; a < 3; ++a) {
      PredictorChoice& c = plan.choices[size_t(f) * 3 + size_t(a)];
      if (f == 0) c.kind = PredictorKind::None;
      else c.r0 = f - 1;
    }
  }
  return plan;
}

bool plan_is_valid(const PredictorPlan& plan, uint32_t F, const ResidualOptions& options) {
  if (plan.order.size() != F || plan.choices.size() != size_t(F) * 3) return false;
  std::vector<uint8_t> decoded(F, 0);
  for (uint32_t f : plan.order) {
    if (f >= F || decoded[f]) return false;
    for (int a = 0; a < 3; ++a)
      if (!predictor_usable(plan.choices[size_t(f) * 3 + size_t(a)], f, decoded, options)) return false;
    decoded[f] = 1;
  }
  return true;
}

namespace {
// Reference frames are written relative to the frame they serve: small numbers.
void write_ref(ByteWriter& w, uint32_t f, uint32_t r) { w.varint(zigzag_encode(int64_t(r) - int64_t(f))); }
uint32_t read_ref(ByteReader& r, uint32_t f) {
  int64_t v = 0;
  if (!add_zigzag_delta(int64_t(f), r.varint(), &v)) return UINT32_MAX;
  return v < 0 || v > int64_t(UINT32_MAX) ? UINT32_MAX : uint32_t(v);
}
}  // namespace

std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q,
                                      const PredictorPlan* plan, const ResidualOptions& options) {
  const uint32_t F = model.meta.frame_count;
  const PredictorPlan fallback = plan ? PredictorPlan() : default_predictor_plan(F);
  const PredictorPlan& p = plan ? *plan : fallback;
  if (!plan_is_valid(p, F, options)) return {};
  if (q.size() != size_t(model.meta.vertex_count) * 3 * F ||
      (options.model_prediction && options.model_prediction->size() != q.size()))
    return {};
  const Traversal trav = build_traversal(model);
  ByteWriter w;
  w.u8(kFormatVersion);
  w.u8(trav.from_faces ? 1 : 0);
  w.u32(values_checksum(q));
  uint32_t expect = 0;  // time order costs one byte per frame: delta to the expected frame
  for (uint32_t f : p.order) {
    write_ref(w, expect, f);
    expect = f + 1;
    for (int a = 0; a < 3; ++a) {
      const PredictorChoice& c = p.choices[size_t(f) * 3 + size_t(a)];
      w.u8(uint8_t(uint8_t(c.kind) | uint8_t(c.spatial) << kSpatialShift));
      if (c.kind == PredictorKind::Reference || c.kind == PredictorKind::Linear) write_ref(w, f, c.r0);
      if (c.kind == PredictorKind::Linear) write_ref(w, f, c.r1);
    }
  }
  RangeEncoder enc;
  AdaptiveIntCoder ints(kContexts, kSignContexts);
  std::vector<int32_t> work(q);  // the walker takes a mutable pointer, shared with decoding
  walk_frames<false>(model, trav, p, options, work.data(), [&](int ctx, int sign_ctx, int64_t* r) {
    ints.encode(enc, ctx, sign_ctx, *r);
    return true;
  });
  const std::vector<uint8_t>& stream = enc.finish();
  w.varint(stream.size());
  w.bytes(stream.data(), stream.size());
  return std::move(w.data());
}

namespace {
// Reads the payload's header and predictor table, leaving `r` at the stream length.
bool read_header(const Model& model, const ResidualOptions& options, ByteReader& r, PredictorPlan* plan,
                 uint32_t* checksum, std::string* error) {
  const uint32_t F = model.meta.frame_count;
  const uint8_t version = r.u8();
  const uint8_t from_faces = r.u8();
  *checksum = r.u32();
  if (!r.ok) return fail(error, "residual stream is truncated");
  if (version != kFormatVersion) return fail(error, "residual stream version " + std::to_string(version) + " is not supported");
  if (from_faces != (model.faces.empty() ? 0 : 1))
    return fail(error, "residual stream was coded with a different neighbour structure (faces present or not)");
  plan->order.clear();
  plan->choices.assign(size_t(F) * 3, PredictorChoice());
  std::vector<uint8_t> decoded(F, 0);
  uint32_t expect = 0;
  for (uint32_t k = 0; k < F; ++k) {
    const uint32_t f = read_ref(r, expect);
    if (!r.ok || f >= F || decoded[f]) return fail(error, "residual frame order is not a permutation of the frames");
    plan->order.push_back(f);
    expect = f + 1;
    for (int a = 0; a < 3; ++a) {
      PredictorChoice& c = plan->choices[size_t(f) * 3 + size_t(a)];
      const uint8_t b = r.u8();
      const uint8_t kind = b & 0x0F, spatial = uint8_t(b >> kSpatialShift);
      if (!r.ok || kind >= kPredictorKindCount || spatial >= kSpatialModeCount)
        return fail(error, "residual predictor table is malformed");
      c.kind = PredictorKind(kind);
      c.spatial = SpatialMode(spatial);
      if (c.kind == PredictorKind::Reference || c.kind == PredictorKind::Linear) c.r0 = read_ref(r, f);
      if (c.kind == PredictorKind::Linear) c.r1 = read_ref(r, f);
      if (!r.ok || !predictor_usable(c, f, decoded, options))
        return fail(error, c.kind == PredictorKind::Model && r.ok
                               ? "residual stream needs the motion model prediction, which was not supplied"
                               : "residual predictor table refers to an unavailable frame");
    }
    decoded[f] = 1;
  }
  return true;
}
}  // namespace

bool decode_predictor_plan(const Model& model, PredictorPlan* plan, std::string* error,
                           const ResidualOptions& options) {
  ByteReader r(model.residual.payload.data(), model.residual.payload.size());
  uint32_t checksum;
  return read_header(model, options, r, plan, &checksum, error);
}

bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error,
                      const ResidualOptions& options) {
  const size_t total = size_t(model.meta.vertex_count) * 3 * model.meta.frame_count;
  if (options.model_prediction && options.model_prediction->size() != total)
    return fail(error, "model prediction has the wrong number of values");
  ByteReader r(model.residual.payload.data(), model.residual.payload.size());
  PredictorPlan plan;
  uint32_t checksum;
  if (!read_header(model, options, r, &plan, &checksum, error)) return false;
  const uint64_t stream_size = r.varint();
  if (!r.ok || stream_size != r.remaining()) return fail(error, "residual stream length does not match the payload");
  const uint8_t* stream = r.take(size_t(stream_size));
  const Traversal trav = build_traversal(model);
  q->assign(total, 0);
  RangeDecoder dec(stream, size_t(stream_size));
  AdaptiveIntCoder ints(kContexts, kSignContexts);
  const bool ok = walk_frames<true>(model, trav, plan, options, q->data(), [&](int ctx, int sign_ctx, int64_t* r) {
    *r = ints.decode(dec, ctx, sign_ctx);
    return !dec.overrun();
  });
  if (!ok || !dec.at_clean_end())
    return fail(error, "residual stream is truncated, corrupted or decodes out of range");
  if (values_checksum(*q) != checksum) return fail(error, "residual stream is corrupted (checksum mismatch)");
  return true;
}

std::vector<int64_t> residual_values(const Model& model, const std::vector<int32_t>& q, const PredictorPlan& plan,
                                     const ResidualOptions& options) {
  std::vector<int64_t> out;
  out.reserve(q.size());
  std::vector<int32_t> work(q);
  walk_frames<false>(model, build_traversal(model), plan, options, work.data(), [&](int, int, int64_t* r) {
    out.push_back(*r);
    return true;
  });
  return out;
}

}  // namespace dcurve
