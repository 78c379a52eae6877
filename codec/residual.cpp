#include "codec/residual.h"

#include <algorithm>
#include <array>

#include "codec/bytes.h"
#include "codec/crc32.h"
#include "codec/error.h"
#include "codec/int_coder.h"
#include "codec/range_coder.h"
#include "codec/record_coder.h"

namespace dcurve {
namespace {

constexpr uint8_t kFormatVersion = 3;
// A plan entry byte: predictor kind in bits 0-3, spatial mode in bits 4-6.
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

// magnitude_class of the mean |residual| over `count` neighbours rounded up, from their sum:
// ceil(sum / count) <= k exactly when sum <= k * count, so no division is needed.
int mean_class(uint32_t sum, uint32_t count) {
  return sum == 0 ? 0 : sum <= count ? 1 : sum <= 2 * count ? 2 : sum <= 4 * count ? 3 : sum <= 8 * count ? 4 : 5;
}

// Per axis, the neighbour class of the context (kNeighbourClasses - 1 without earlier
// neighbours) and the sum of the earlier neighbours' residuals (the sign context): one pass
// over the neighbours for the three axes.
void neighbour_contexts(const Traversal& trav, uint32_t pos, const int8_t* rf, int classes[3], int sums[3]) {
  const uint32_t nb_begin = trav.nb_offsets[pos], nb_end = trav.nb_offsets[pos + 1];
  uint32_t magnitude[3] = {0, 0, 0};
  sums[0] = sums[1] = sums[2] = 0;
  for (uint32_t n = nb_begin; n < nb_end; ++n) {
    const int8_t* r = rf + size_t(trav.nb[n]) * 3;
    for (int a = 0; a < 3; ++a) {
      magnitude[a] += uint32_t(r[a] < 0 ? -r[a] : r[a]);
      sums[a] += r[a];
    }
  }
  for (int a = 0; a < 3; ++a)
    classes[a] = nb_begin == nb_end ? kNeighbourClasses - 1 : mean_class(magnitude[a], nb_end - nb_begin);
}

int sign3(int64_t v) { return v < 0 ? 0 : v == 0 ? 1 : 2; }

// Residuals are kept, clamped to a byte, for the contexts of later vertices and frames.
int8_t clamp8(int64_t r) { return int8_t(r < -127 ? -127 : r > 127 ? 127 : r); }

// Which candidate each cluster uses and the motion maps are coded in the stream, at the
// start of the cluster: an index (a "same as the previous cluster" flag, then the index
// among the others in fixed-length binary with a tree of contexts) and, per Motion axis,
// the four numbers of its row as differences to the previous row coded for that axis in
// this frame (neighbouring patches move alike).
struct SideModels {
  BitModel same;
  std::array<BitModel, 32> index_tree;
  AdaptiveIntCoder params{3, 1};  // contexts: diagonal, off-diagonal, translation
};
// Context of entry e (0..2 matrix column, 3 translation) of the row of `axis`.
int param_context(int e, int axis) { return e == 3 ? 2 : e == axis ? 0 : 1; }

int index_bits(uint32_t others) {
  int b = 0;
  while ((uint32_t(1) << b) < others) ++b;
  return b;
}

// Frame f's Model predictor values: read in place from options.model_prediction, else
// computed into the workspace; null when the walk has none.
const int32_t* model_values(const ResidualOptions& options, uint32_t f, size_t stride, ResidualWorkspace& ws) {
  if (options.model_prediction) return options.model_prediction->data() + size_t(f) * stride;
  if (!options.model_frames) return nullptr;
  ws.model_frame.resize(stride);
  options.model_frames->frame(f, ws.model_frame.data());
  return ws.model_frame.data();
}

// Walks the frames in decoding order, calling coder.residual(ctx, sign_ctx, &r) for every
// residual r, coder.index(K, previous, &j) at every cluster of a frame with K > 1
// candidates and coder.row(previous, &row) for every Motion axis of the cluster. When
// decoding, the coder writes r, j and the rows (the walker fills q and plan); otherwise the
// walker computes r from q and the coder codes or records it. One body for all uses so
// they cannot drift apart.
template <bool kDecode, class Coder>
bool walk_frames(uint32_t V, const Traversal& trav, PredictorPlan& plan, const ResidualOptions& options,
                 int32_t* q, Coder& coder, ResidualWorkspace& ws) {
  const uint32_t S = plan.cluster_size, clusters = cluster_count(V, S);
  const size_t stride = size_t(V) * 3;
  std::vector<int64_t>& base = ws.base;
  std::vector<int8_t>& res = ws.residuals;
  res.assign(stride * plan.order.size(), 0);
  const int8_t* previous = nullptr;  // residuals of the frame coded last
  SpatialWeightsCache geometry(options.weights_source);
  if constexpr (kDecode) plan.stream_bytes.assign(plan.order.size(), 0);
  for (uint32_t f : plan.order) {
    [[maybe_unused]] size_t frame_start = 0;
    if constexpr (kDecode) frame_start = coder.dec.position();
    FramePredictors& fp = plan.frames[f];
    const uint32_t K = uint32_t(fp.candidates.size());
    base.resize(size_t(K) * stride);
    const int32_t* model_frame = model_values(options, f, stride, ws);
    for (uint32_t j = 0; j < K; ++j)
      for (int a = 0; a < 3; ++a)
        if (fp.candidates[j][size_t(a)].kind == PredictorKind::Linear)  // the others are read in place
          base_prediction(fp.candidates[j][size_t(a)], f, a, V, q, options, &base[(size_t(j) * 3 + size_t(a)) * V]);
    const uint32_t blocks = motion_block_count(V, plan), block_size = plan.motion_block;
    if (kDecode) {
      fp.cluster_candidate.assign(K > 1 ? clusters : 0, 0);
      fp.transforms.assign(size_t(blocks) * K, MotionTransform());
    }
    std::vector<uint8_t> have_map(size_t(blocks) * K, 0);  // the map was coded already
    std::vector<std::array<int64_t, 9>> centres(size_t(blocks) * K);
    int32_t* qf = q + size_t(f) * stride;
    int8_t* rf = &res[size_t(f) * stride];
    uint32_t prev_j = 0;
    MotionRow prev_row[3];
    for (uint32_t k = 0; k < clusters; ++k) {
      const uint32_t begin = k * S, end = std::min(V, begin + S);
      uint32_t j = fp.cluster_candidate.empty() ? 0 : fp.cluster_candidate[k];
      if (K > 1) {
        if (!coder.index(K, prev_j, &j)) return false;
        if (kDecode) fp.cluster_candidate[k] = uint8_t(j);
      }
      prev_j = j;
      const PredictorChoice* choice = fp.candidates[j].data();
      const uint32_t block = k / block_size;
      const size_t slot = size_t(block) * K + j;
      const MotionRow* rows = fp.transforms.empty() ? nullptr : fp.transforms[slot].row;
      const int64_t* centre = centres[slot].data();
      const int32_t* ref[3];
      const int8_t* source[3];
      const int32_t* weights[3];
      geometry.for_choice(trav, q, choice, weights);
      for (int a = 0; a < 3; ++a) {
        const PredictorChoice& c = choice[a];
        source[a] = has_reference(c.kind) ? &res[size_t(c.r0) * stride] : previous;
        ref[a] = q + size_t(c.r0) * stride;
        if (c.kind != PredictorKind::Motion || have_map[slot]) continue;
        MotionRow& row = fp.transforms[slot].row[a];
        if (!coder.row(a, prev_row[a], &row)) return false;
        prev_row[a] = row;
        const uint32_t block_begin = block * block_size * S;
        const uint32_t block_end = uint32_t(std::min<uint64_t>(V, (uint64_t(block) + 1) * block_size * S));
        cluster_centre(ref[a], trav, block_begin, block_end, &centres[slot][size_t(a) * 3]);
      }
      for (int a = 0; a < 3; ++a) have_map[slot] |= choice[a].kind == PredictorKind::Motion;
      const int64_t* bj = &base[size_t(j) * stride];
      const int32_t* model_f = model_frame;
      auto base_of = [&](uint32_t u, int a) -> int64_t {
        switch (choice[a].kind) {
          case PredictorKind::None: return 0;
          case PredictorKind::Reference: return ref[a][size_t(u) * 3 + size_t(a)];
          case PredictorKind::Motion: return motion_prediction(rows[a], a, centre + 3 * a, ref[a] + size_t(u) * 3);
          case PredictorKind::Model: return model_f[size_t(u) * 3 + size_t(a)];
          case PredictorKind::Linear: break;
        }
        return bj[size_t(a) * V + u];
      };
      for (uint32_t pos = begin; pos < end; ++pos) {
        const uint32_t v = trav.order[pos];
        uint32_t axis_max = 0;
        int64_t preds[3];
        vertex_prediction(choice, trav, pos, qf, base_of, preds, weights);
        int nb_classes[3], nb_sums[3];
        neighbour_contexts(trav, pos, rf, nb_classes, nb_sums);
        for (int a = 0; a < 3; ++a) {
          const int64_t pred = preds[a];
          const int nb_class = nb_classes[a], nb_sum = nb_sums[a];
          const size_t i = size_t(v) * 3 + size_t(a);
          const int t = source[a] ? source[a][i] : 0;
          const int t_class = std::min(magnitude_class(uint32_t(t < 0 ? -t : t)), kTemporalClasses - 1);
          const int a_class = a == 0 ? kAxisClasses - 1 : std::min(magnitude_class(axis_max), kAxisClasses - 2);
          const int ctx = (nb_class * kTemporalClasses + t_class) * kAxisClasses + a_class;
          const int sign_ctx = sign3(t) * 3 + sign3(nb_sum);
          int64_t r;
          if constexpr (kDecode) {
            if (!coder.residual(ctx, sign_ctx, &r)) return false;
            const int64_t value = pred + r;
            if (value < INT32_MIN || value > INT32_MAX) return false;
            qf[i] = int32_t(value);
          } else {
            r = int64_t(qf[i]) - pred;
            coder.residual(ctx, sign_ctx, &r);
          }
          rf[i] = clamp8(r);
          axis_max = std::max(axis_max, uint32_t(rf[i] < 0 ? -rf[i] : rf[i]));
        }
      }
    }
    previous = rf;
    if constexpr (kDecode) plan.stream_bytes[f] = uint32_t(coder.dec.position() - frame_start);
  }
  return true;
}

// The coders walk_frames drives: writing the range-coded stream, reading it, recording
// the residuals.
struct StreamWriter {
  RangeEncoder enc;
  AdaptiveIntCoder ints{kContexts, kSignContexts};
  SideModels side;
  bool residual(int ctx, int sign_ctx, int64_t* r) {
    ints.encode(enc, ctx, sign_ctx, *r);
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

struct StreamReader {
  RangeDecoder dec;
  AdaptiveIntCoder ints{kContexts, kSignContexts};
  SideModels side;
  StreamReader(const uint8_t* data, size_t size) : dec(data, size) {}
  bool residual(int ctx, int sign_ctx, int64_t* r) {
    *r = ints.decode(dec, ctx, sign_ctx);
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

struct ResidualRecorder {
  std::vector<int64_t>* out;
  bool residual(int, int, int64_t* r) {
    out->push_back(*r);
    return true;
  }
  bool index(uint32_t, uint32_t, uint32_t*) { return true; }
  bool row(int, const MotionRow&, MotionRow*) { return true; }
};

// CRC-32C of the values as little-endian int32: a stream that still decodes to in-range
// values against another prediction (a damaged model) is caught.
uint32_t values_checksum(const int32_t* q, size_t count) {
  uint32_t crc = 0;
  uint8_t chunk[4096];
  for (size_t i = 0; i < count;) {
    size_t n = 0;
    for (; n + 4 <= sizeof chunk && i < count; ++i, n += 4) {
      const uint32_t u = uint32_t(q[i]);
      for (int b = 0; b < 4; ++b) chunk[n + size_t(b)] = uint8_t(u >> (8 * b));
    }
    crc = crc32c(chunk, n, crc);
  }
  return crc;
}

}  // namespace

PredictorPlan uniform_plan(const std::vector<uint32_t>& order, const std::vector<PredictorChoice>& choices) {
  PredictorPlan plan;
  plan.order = order;
  plan.frames.resize(choices.size() / 3);
  for (size_t f = 0; f < plan.frames.size(); ++f)
    plan.frames[f].candidates = {{choices[f * 3], choices[f * 3 + 1], choices[f * 3 + 2]}};
  return plan;
}

PredictorPlan default_predictor_plan(uint32_t frame_count) {
  std::vector<PredictorChoice> choices(size_t(frame_count) * 3);
  std::vector<uint32_t> order;
  for (uint32_t f = 0; f < frame_count; ++f) {
    order.push_back(f);
    for (int a = 0; a < 3; ++a) {
      PredictorChoice& c = choices[size_t(f) * 3 + size_t(a)];
      if (f == 0) c.kind = PredictorKind::None;
      else c.r0 = f - 1;
    }
  }
  return uniform_plan(order, choices);
}

bool geometry_frames_within_bound(const FramePredictors& fp) {
  std::vector<uint32_t> frames;
  for (const auto& candidate : fp.candidates)
    for (const PredictorChoice& c : candidate)
      if (uses_geometry(c.spatial) && std::find(frames.begin(), frames.end(), c.g) == frames.end())
        frames.push_back(c.g);
  return frames.size() <= kMaxGeometryFrames;
}

bool plan_is_valid(const PredictorPlan& plan, uint32_t F, uint32_t V, const ResidualOptions& options) {
  if (plan.order.size() != F || plan.frames.size() != F || plan.cluster_size == 0 || plan.motion_block == 0)
    return false;
  const uint32_t clusters = cluster_count(V, plan.cluster_size), blocks = motion_block_count(V, plan);
  std::vector<uint8_t> decoded(F, 0);
  for (uint32_t f : plan.order) {
    if (f >= F || decoded[f]) return false;
    const FramePredictors& fp = plan.frames[f];
    if (fp.candidates.empty() || fp.candidates.size() > kMaxCandidates) return false;
    if (!geometry_frames_within_bound(fp)) return false;
    if (!fp.cluster_candidate.empty() && fp.cluster_candidate.size() != clusters) return false;
    for (uint8_t j : fp.cluster_candidate)
      if (j >= fp.candidates.size()) return false;
    for (const auto& candidate : fp.candidates)
      for (const PredictorChoice& c : candidate) {
        if (!predictor_usable(c, f, decoded, options)) return false;
        if (c.kind == PredictorKind::Motion && fp.transforms.size() != size_t(blocks) * fp.candidates.size())
          return false;
      }
    for (const MotionTransform& t : fp.transforms)
      for (const MotionRow& row : t.row)
        if (!motion_row_valid(row)) return false;
    decoded[f] = 1;
  }
  return true;
}

namespace {
// Reference frames are written relative to the frame they serve: small numbers.
void write_ref(ByteWriter& w, uint32_t f, uint32_t r) { w.varint(zigzag_encode(int64_t(r) - int64_t(f))); }
uint32_t read_ref(RecordReader& r, uint32_t f) {
  int64_t v = 0;
  if (!add_zigzag_delta(int64_t(f), r.varint(), &v)) return UINT32_MAX;
  return v < 0 || v > int64_t(UINT32_MAX) ? UINT32_MAX : uint32_t(v);
}
}  // namespace

ResidualPlan single_chunk_plan(const PredictorPlan& plan) {
  ResidualPlan r;
  r.chunk_frames = uint32_t(std::max<size_t>(plan.order.size(), 1));
  r.chunks.push_back(plan);
  return r;
}

ResidualPlan default_chunked_plan(uint32_t F, uint32_t K) {
  ResidualPlan r;
  r.chunk_frames = K;
  for (uint32_t c = 0; c < chunk_count(F, K); ++c) r.chunks.push_back(default_predictor_plan(chunk_span(F, K, c).count));
  return r;
}

std::vector<CodedFrame> coded_frames(const ResidualPlan& plan) {
  std::vector<CodedFrame> out;
  for (size_t c = 0; c < plan.chunks.size(); ++c) {
    const PredictorPlan& chunk = plan.chunks[c];
    const uint32_t first = uint32_t(c) * plan.chunk_frames;
    for (uint32_t f : chunk.order) out.push_back({first + f, &chunk, &chunk.frames[f]});
  }
  return out;
}

namespace {
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

namespace {
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

bool read_residual_index(const uint8_t* payload, size_t size, uint32_t F, bool has_faces, uint64_t data_limit,
                         ResidualIndex* index, std::string* error) {
  ByteReader r(payload, size);
  const uint8_t version = r.u8();
  const uint8_t from_faces = r.u8();
  const uint64_t chunk_frames = r.varint(), count = r.varint();
  if (!r.ok) return fail(error, "residual payload is truncated");
  if (version != kFormatVersion) return fail(error, "residual payload version " + std::to_string(version) + " is not supported");
  if (from_faces > 1 || from_faces != (has_faces ? 1 : 0))
    return fail(error, "residual payload was coded with a different neighbour structure (faces present or not)");
  if (chunk_frames == 0 || chunk_frames > F) return fail(error, "residual chunk length is out of range");
  if (count != chunk_count(F, uint32_t(chunk_frames)))
    return fail(error, "residual chunk index disagrees with the frame count");
  if (count * 6 > r.remaining()) return fail(error, "residual chunk index is truncated");
  index->from_faces = from_faces != 0;
  index->chunk_frames = uint32_t(chunk_frames);
  index->chunks.assign(size_t(count), ChunkEntry());
  uint64_t end = 0;
  for (ChunkEntry& e : index->chunks) {
    e.offset = r.varint();
    e.size = r.varint();
    e.crc = r.u32();
    if (!r.ok) return fail(error, "residual chunk index is truncated");
    if (e.offset != end) return fail(error, "residual chunk index has a gap or an overlap between chunks");
    if (e.size == 0 || e.size > data_limit - end) return fail(error, "residual chunk index points outside the data");
    end += e.size;
  }
  index->index_bytes = r.position();
  index->data_bytes = end;
  return true;
}

namespace {
// The options of one chunk's walk: a whole-animation Model prediction cut to the chunk's
// frames (into *storage).
ResidualOptions options_for_chunk(const ResidualOptions& options, ChunkSpan span, size_t stride,
                                  std::vector<int32_t>* storage) {
  ResidualOptions out = options;
  if (options.model_prediction) {
    const auto from = options.model_prediction->begin() + ptrdiff_t(stride * span.first);
    storage->assign(from, from + ptrdiff_t(stride * span.count));
    out.model_prediction = storage;
  }
  return out;
}
}  // namespace

std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                                      const ResidualOptions& options) {
  const uint32_t F = model.meta.frame_count, V = model.meta.vertex_count, K = plan.chunk_frames;
  const size_t stride = size_t(V) * 3;
  if (K == 0 || plan.chunks.size() != chunk_count(F, K) || q.size() != stride * F ||
      (options.model_prediction && options.model_prediction->size() != q.size()))
    return {};
  Traversal owned;
  const Traversal& trav = traversal_for(model, options, &owned);
  ByteWriter data;
  std::vector<ChunkEntry> entries;
  for (uint32_t c = 0; c < plan.chunks.size(); ++c) {
    const ChunkSpan span = chunk_span(F, K, c);
    std::vector<int32_t> prediction;
    const ResidualOptions chunk_options = options_for_chunk(options, span, stride, &prediction);
    const std::vector<uint8_t> bytes =
        encode_residual_chunk(V, trav, q.data() + stride * span.first, span.count, plan.chunks[c], chunk_options);
    if (bytes.empty()) return {};
    entries.push_back({data.size(), bytes.size(), crc32c(bytes.data(), bytes.size())});
    data.bytes(bytes.data(), bytes.size());
  }
  ByteWriter w;
  w.u8(kFormatVersion);
  w.u8(trav.from_faces ? 1 : 0);
  w.varint(K);
  w.varint(entries.size());
  for (const ChunkEntry& e : entries) {
    w.varint(e.offset);
    w.varint(e.size);
    w.u32(e.crc);
  }
  w.bytes(data.data().data(), data.size());
  return std::move(w.data());
}

std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q, const PredictorPlan* plan,
                                      const ResidualOptions& options) {
  return encode_residuals(model, q, single_chunk_plan(plan ? *plan : default_predictor_plan(model.meta.frame_count)),
                          options);
}

namespace {
// Decodes every chunk of the payload into q, filling plan (with its per-cluster choices).
bool decode_all(const Model& model, std::vector<int32_t>* q, ResidualPlan* plan, std::string* error,
                const ResidualOptions& options) {
  const uint32_t F = model.meta.frame_count, V = model.meta.vertex_count;
  const size_t stride = size_t(V) * 3, total = stride * F;
  if (options.model_prediction && options.model_prediction->size() != total)
    return fail(error, "model prediction has the wrong number of values");
  const std::vector<uint8_t>& payload = model.residual.payload;
  ResidualIndex index;
  if (!read_residual_index(payload.data(), payload.size(), F, !model.faces.empty(), UINT64_MAX, &index, error))
    return false;
  if (index.data_bytes != payload.size() - index.index_bytes)
    return fail(error, "residual chunk index does not match the payload's chunk data");
  Traversal owned;
  const Traversal& trav = traversal_for(model, options, &owned);
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
    const ResidualOptions chunk_options = options_for_chunk(options, span, stride, &prediction);
    std::string why;
    if (!decode_residual_chunk(V, trav, bytes, size_t(e.size), span.count, q->data() + stride * span.first,
                               chunk_options, &ws, &why))
      return fail(error, "residual chunk " + std::to_string(c) + ": " + why);
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
  if (!read_residual_index(payload.data(), payload.size(), F, !model.faces.empty(), UINT64_MAX, &index, error))
    return false;
  if (index.data_bytes != payload.size() - index.index_bytes)
    return fail(error, "residual chunk index does not match the payload's chunk data");
  plan->chunk_frames = index.chunk_frames;
  plan->chunks.assign(index.chunks.size(), PredictorPlan());
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

std::vector<int64_t> residual_values(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                                     const ResidualOptions& options) {
  const uint32_t F = model.meta.frame_count, V = model.meta.vertex_count;
  const size_t stride = size_t(V) * 3;
  // A plan read without its clusters has no motion maps: nothing to walk with.
  const uint32_t K = plan.chunk_frames;
  if (K == 0 || plan.chunks.size() != chunk_count(F, K)) return {};
  for (const PredictorPlan& chunk : plan.chunks) {
    const uint32_t blocks = motion_block_count(V, chunk);
    for (const FramePredictors& fp : chunk.frames)
      for (const auto& candidate : fp.candidates)
        for (const PredictorChoice& c : candidate)
          if (c.kind == PredictorKind::Motion && fp.transforms.size() != size_t(blocks) * fp.candidates.size())
            return {};
  }
  std::vector<int64_t> out;
  out.reserve(q.size());
  Traversal owned;
  const Traversal& trav = traversal_for(model, options, &owned);
  ResidualWorkspace ws;
  for (uint32_t c = 0; c < plan.chunks.size(); ++c) {
    const ChunkSpan span = chunk_span(F, K, c);
    std::vector<int32_t> work(q.begin() + ptrdiff_t(stride * span.first),
                              q.begin() + ptrdiff_t(stride * (span.first + span.count)));
    std::vector<int32_t> prediction;
    const ResidualOptions chunk_options = options_for_chunk(options, span, stride, &prediction);
    PredictorPlan p = plan.chunks[c];
    ResidualRecorder recorder{&out};
    walk_frames<false>(V, trav, p, chunk_options, work.data(), recorder, ws);
  }
  return out;
}

}  // namespace dcurve
