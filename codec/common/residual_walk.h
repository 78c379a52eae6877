// The walk over a chunk's frames that the writer (codec/compress/residual_encoder.cpp), the
// reader (codec/decompress/residual_decoder.cpp) and residual_values
// (codec/compress/residual_values.cpp) of the residual layer all run, with the contexts,
// the models of the side information and the checks they share: one body for all so they
// cannot drift apart (format_spec/residual.md).
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/bit_model.h"
#include "codec/common/crc32.h"
#include "codec/common/int_coder.h"
#include "codec/common/motion_compensation.h"
#include "codec/common/predictors.h"
#include "codec/common/residual.h"

namespace dcurve {
namespace residual_walk {

// Payload versions: 4 (files 3.1) codes, before every block of kZeroBlock traversal
// positions of a cluster, whether all its residuals are zero; 3 (files 3.0, still read)
// has no such flags. A zero block costs the reader its predictions only: most blocks of
// a frame the motion model predicts within the grid step.
constexpr uint8_t kFormatVersion = 4, kOldestFormatVersion = 3;
constexpr uint32_t kZeroBlock = 16;
constexpr int kZeroBlockContexts = 9;
inline bool has_zero_block_flags(uint8_t payload_version) { return payload_version >= 4; }
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

inline int magnitude_class(uint32_t m) {
  return m < 3 ? int(m) : m <= 4 ? 3 : m <= 8 ? 4 : 5;
}

// magnitude_class of the mean |residual| over `count` neighbours rounded up, from their sum:
// ceil(sum / count) <= k exactly when sum <= k * count, so no division is needed.
inline int mean_class(uint32_t sum, uint32_t count) {
  return sum == 0 ? 0 : sum <= count ? 1 : sum <= 2 * count ? 2 : sum <= 4 * count ? 3 : sum <= 8 * count ? 4 : 5;
}

// Per axis, the neighbour class of the context (kNeighbourClasses - 1 without earlier
// neighbours) and the sum of the earlier neighbours' residuals (the sign context): one pass
// over the neighbours for the three axes.
inline void neighbour_contexts(const Traversal& trav, uint32_t pos, const int8_t* rf, int classes[3], int sums[3]) {
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

inline int sign3(int64_t v) { return v < 0 ? 0 : v == 0 ? 1 : 2; }

// Residuals are kept, clamped to a byte, for the contexts of later vertices and frames.
inline int8_t clamp8(int64_t r) { return int8_t(r < -127 ? -127 : r > 127 ? 127 : r); }

// Which candidate each cluster uses and the motion maps are coded in the stream, at the
// start of the cluster: an index (a "same as the previous cluster" flag, then the index
// among the others in fixed-length binary with a tree of contexts) and, per Motion axis,
// the four numbers of its row as differences to the previous row coded for that axis in
// this frame (neighbouring patches move alike).
struct SideModels {
  BitModel same;
  std::array<BitModel, 32> index_tree;
  std::array<BitModel, kZeroBlockContexts> zero_block;  // bit 1: every residual of the block is zero
  AdaptiveIntCoder params{3, 1};  // contexts: diagonal, off-diagonal, translation
};
// Context of entry e (0..2 matrix column, 3 translation) of the row of `axis`.
inline int param_context(int e, int axis) { return e == 3 ? 2 : e == axis ? 0 : 1; }

inline int index_bits(uint32_t others) {
  int b = 0;
  while ((uint32_t(1) << b) < others) ++b;
  return b;
}

// Frame f's Model predictor values: read in place from options.model_prediction, else
// computed into the workspace; null when the walk has none.
inline const int32_t* model_values(const ResidualOptions& options, uint32_t f, size_t stride, ResidualWorkspace& ws) {
  if (options.model_prediction) return options.model_prediction->data() + size_t(f) * stride;
  if (!options.model_frames) return nullptr;
  ws.model_frame.resize(stride);
  options.model_frames->frame(f, ws.model_frame.data());
  return ws.model_frame.data();
}

// The base prediction of vertex u, axis a, under the predictors one cluster uses.
struct ClusterBase {
  const PredictorChoice* choice = nullptr;
  const int32_t* ref[3] = {nullptr, nullptr, nullptr};
  const MotionRow* rows = nullptr;
  const int64_t* centre = nullptr;
  const int32_t* model = nullptr;
  const int64_t* linear = nullptr;  // the frame's Linear predictions
  const uint32_t* linear_at = nullptr;
  uint32_t V = 0;
  int64_t operator()(uint32_t u, int a) const {
    switch (choice[a].kind) {
      case PredictorKind::None: return 0;
      case PredictorKind::Reference: return ref[a][size_t(u) * 3 + size_t(a)];
      case PredictorKind::Motion: return motion_prediction(rows[a], a, centre + 3 * a, ref[a] + size_t(u) * 3);
      case PredictorKind::Model: return model[size_t(u) * 3 + size_t(a)];
      case PredictorKind::Linear: break;
    }
    return linear[linear_at[a] * size_t(V) + u];
  }
};

// What coding a cluster's vertices needs besides the frame's values: the base predictions,
// the residuals giving the temporal contexts and the spatial weight tables, per axis.
struct ClusterView {
  ClusterBase base;
  const int8_t* source[3] = {nullptr, nullptr, nullptr};
  const int32_t* weights[3] = {nullptr, nullptr, nullptr};
};

// Codes (or decodes) the three residuals of traversal position pos; qf and rf are the
// frame's values and residuals.
template <bool kDecode, class Coder>
bool code_vertex(const Traversal& trav, uint32_t pos, const ClusterView& view, int32_t* qf, int8_t* rf, Coder& coder) {
  const uint32_t v = trav.order[pos];
  int64_t preds[3];
  vertex_prediction(view.base.choice, trav, pos, qf, view.base, preds, view.weights);
  int nb_classes[3], nb_sums[3];
  neighbour_contexts(trav, pos, rf, nb_classes, nb_sums);
  uint32_t axis_max = 0;
  for (int a = 0; a < 3; ++a) {
    const size_t i = size_t(v) * 3 + size_t(a);
    const int t = view.source[a] ? view.source[a][i] : 0;
    const int t_class = std::min(magnitude_class(uint32_t(t < 0 ? -t : t)), kTemporalClasses - 1);
    const int a_class = a == 0 ? kAxisClasses - 1 : std::min(magnitude_class(axis_max), kAxisClasses - 2);
    const int ctx = (nb_classes[a] * kTemporalClasses + t_class) * kAxisClasses + a_class;
    const int sign_ctx = sign3(t) * 3 + sign3(nb_sums[a]);
    int64_t r;
    if constexpr (kDecode) {
      if (!coder.residual(ctx, sign_ctx, &r)) return false;
      const int64_t value = preds[a] + r;
      if (value < INT32_MIN || value > INT32_MAX) return false;
      qf[i] = int32_t(value);
    } else {
      r = int64_t(qf[i]) - preds[a];
      coder.residual(ctx, sign_ctx, &r);
    }
    rf[i] = clamp8(r);
    axis_max = std::max(axis_max, uint32_t(rf[i] < 0 ? -rf[i] : rf[i]));
  }
  return true;
}

// Whether every residual of positions [begin, end) is zero (the writer's side of a block
// flag: the values are known).
inline bool block_is_zero(const Traversal& trav, uint32_t begin, uint32_t end, const ClusterView& view,
                          const int32_t* qf) {
  for (uint32_t pos = begin; pos < end; ++pos) {
    int64_t preds[3];
    vertex_prediction(view.base.choice, trav, pos, qf, view.base, preds, view.weights);
    const size_t i = size_t(trav.order[pos]) * 3;
    for (int a = 0; a < 3; ++a)
      if (preds[a] != qf[i + size_t(a)]) return false;
  }
  return true;
}

// The reader's side of a zero block: each value is its prediction (residuals stay zero).
inline bool predict_zero_block(const Traversal& trav, uint32_t begin, uint32_t end, const ClusterView& view,
                               int32_t* qf) {
  for (uint32_t pos = begin; pos < end; ++pos) {
    int64_t preds[3];
    vertex_prediction(view.base.choice, trav, pos, qf, view.base, preds, view.weights);
    const size_t i = size_t(trav.order[pos]) * 3;
    for (int a = 0; a < 3; ++a) {
      if (preds[a] < INT32_MIN || preds[a] > INT32_MAX) return false;
      qf[i + size_t(a)] = int32_t(preds[a]);
    }
  }
  return true;
}

// The block flags of the frame being coded and of the frame coded before it (the context).
struct BlockFlags {
  std::vector<uint8_t>& current;
  const std::vector<uint8_t>& previous;  // empty for a chunk's first frame
  // Context: the previous block of this frame and the same block of the previous frame,
  // each absent, all zero or not.
  int context() const {
    const size_t b = current.size();
    const int left = b == 0 ? 0 : current[b - 1] ? 1 : 2;
    const int above = b >= previous.size() ? 0 : previous[b] ? 1 : 2;
    return left * 3 + above;
  }
};

// Codes the positions [begin, end) of one cluster: block by block, each behind its flag
// when the payload has them.
template <bool kDecode, class Coder>
bool code_cluster(const Traversal& trav, uint32_t begin, uint32_t end, const ClusterView& view, int32_t* qf,
                  int8_t* rf, BlockFlags* flags, Coder& coder) {
  for (uint32_t b0 = begin; b0 < end; b0 += kZeroBlock) {
    const uint32_t b1 = std::min(end, b0 + kZeroBlock);
    if (flags) {
      bool zero = false;
      if constexpr (!kDecode) zero = block_is_zero(trav, b0, b1, view, qf);
      if (!coder.zero_block(flags->context(), &zero)) return false;
      flags->current.push_back(zero ? 1 : 0);
      if (zero) {
        // Residuals are already zero (walk_frames clears them); the writer's values equal their predictions.
        if (kDecode && !predict_zero_block(trav, b0, b1, view, qf)) return false;
        continue;
      }
    }
    for (uint32_t pos = b0; pos < b1; ++pos)
      if (!code_vertex<kDecode>(trav, pos, view, qf, rf, coder)) return false;
  }
  return true;
}

// Computes the frame's Linear predictions, V values per (candidate, axis) that uses one;
// linear_at[j * 3 + a] says where.
inline void linear_predictions(const FramePredictors& fp, uint32_t f, uint32_t V, const int32_t* q,
                               const ResidualOptions& options, std::vector<int64_t>* base,
                               std::array<uint32_t, kMaxCandidates * 3>* linear_at) {
  const uint32_t K = uint32_t(fp.candidates.size());
  uint32_t linears = 0;
  for (uint32_t j = 0; j < K; ++j)
    for (int a = 0; a < 3; ++a)
      if (fp.candidates[j][size_t(a)].kind == PredictorKind::Linear) (*linear_at)[j * 3 + uint32_t(a)] = linears++;
  base->resize(size_t(linears) * V);
  for (uint32_t j = 0; j < K; ++j)
    for (int a = 0; a < 3; ++a)
      if (fp.candidates[j][size_t(a)].kind == PredictorKind::Linear)
        base_prediction(fp.candidates[j][size_t(a)], f, a, V, q, options,
                        &(*base)[(*linear_at)[j * 3 + uint32_t(a)] * size_t(V)]);
}

// Walks the frames in decoding order, calling coder.residual(ctx, sign_ctx, &r) for every
// residual r, coder.zero_block(ctx, &zero) before every block of kZeroBlock positions (when
// options.zero_block_flags), coder.index(K, previous, &j) at every cluster of a frame with
// K > 1 candidates and coder.row(previous, &row) for every Motion axis of the cluster. When
// decoding, the coder writes r, zero, j and the rows (the walker fills q and plan);
// otherwise the walker computes them from q and the coder codes or records them. One body
// for all uses so they cannot drift apart.
template <bool kDecode, class Coder>
bool walk_frames(uint32_t V, const Traversal& trav, PredictorPlan& plan, const ResidualOptions& options,
                 int32_t* q, Coder& coder, ResidualWorkspace& ws) {
  const uint32_t S = plan.cluster_size, clusters = cluster_count(V, S);
  const size_t stride = size_t(V) * 3;
  std::vector<int8_t>& res = ws.residuals;
  res.assign(stride * plan.order.size(), 0);
  const int8_t* previous = nullptr;  // residuals of the frame coded last
  ws.block_flags.clear();
  ws.previous_block_flags.clear();
  SpatialWeightsCache geometry(options.weights_source);
  if constexpr (kDecode) plan.stream_bytes.assign(plan.order.size(), 0);
  for (uint32_t f : plan.order) {
    [[maybe_unused]] size_t frame_start = 0;
    if constexpr (kDecode) frame_start = coder.dec.position();
    FramePredictors& fp = plan.frames[f];
    const uint32_t K = uint32_t(fp.candidates.size());
    std::array<uint32_t, kMaxCandidates * 3> linear_at{};
    linear_predictions(fp, f, V, q, options, &ws.base, &linear_at);
    const uint32_t blocks = motion_block_count(V, plan), block_size = plan.motion_block;
    if (kDecode) {
      fp.cluster_candidate.assign(K > 1 ? clusters : 0, 0);
      fp.transforms.assign(size_t(blocks) * K, MotionTransform());
    }
    std::vector<uint8_t> have_map(size_t(blocks) * K, 0);  // the map was coded already
    std::vector<std::array<int64_t, 9>> centres(size_t(blocks) * K);
    int32_t* qf = q + size_t(f) * stride;
    int8_t* rf = &res[size_t(f) * stride];
    std::swap(ws.block_flags, ws.previous_block_flags);
    ws.block_flags.clear();
    BlockFlags flags{ws.block_flags, ws.previous_block_flags};
    ClusterView view;
    view.base.model = model_values(options, f, stride, ws);
    view.base.linear = ws.base.data();
    view.base.V = V;
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
      geometry.for_choice(trav, q, choice, view.weights);
      for (int a = 0; a < 3; ++a) {
        const PredictorChoice& c = choice[a];
        view.source[a] = has_reference(c.kind) ? &res[size_t(c.r0) * stride] : previous;
        view.base.ref[a] = q + size_t(c.r0) * stride;
        if (c.kind != PredictorKind::Motion || have_map[slot]) continue;
        MotionRow& row = fp.transforms[slot].row[a];
        if (!coder.row(a, prev_row[a], &row)) return false;
        prev_row[a] = row;
        const uint32_t block_begin = block * block_size * S;
        const uint32_t block_end = uint32_t(std::min<uint64_t>(V, (uint64_t(block) + 1) * block_size * S));
        cluster_centre(view.base.ref[a], trav, block_begin, block_end, &centres[slot][size_t(a) * 3]);
      }
      for (int a = 0; a < 3; ++a) have_map[slot] |= choice[a].kind == PredictorKind::Motion;
      view.base.choice = choice;
      view.base.rows = fp.transforms.empty() ? nullptr : fp.transforms[slot].row;
      view.base.centre = centres[slot].data();
      view.base.linear_at = &linear_at[j * 3];
      if (!code_cluster<kDecode>(trav, begin, end, view, qf, rf, options.zero_block_flags ? &flags : nullptr, coder))
        return false;
    }
    previous = rf;
    if constexpr (kDecode) plan.stream_bytes[f] = uint32_t(coder.dec.position() - frame_start);
  }
  return true;
}

// CRC-32C of the values as little-endian int32: a stream that still decodes to in-range
// values against another prediction (a damaged model) is caught.
inline uint32_t values_checksum(const int32_t* q, size_t count) {
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  return crc32c(q, count * sizeof(int32_t));  // the values' memory is their little-endian bytes
#else
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
#endif
}

// The options of one chunk's walk: a whole-animation Model prediction cut to the chunk's
// frames (into *storage).
inline ResidualOptions options_for_chunk(const ResidualOptions& options, ChunkSpan span, size_t stride,
                                         std::vector<int32_t>* storage) {
  ResidualOptions out = options;
  if (options.model_prediction) {
    const auto from = options.model_prediction->begin() + ptrdiff_t(stride * span.first);
    storage->assign(from, from + ptrdiff_t(stride * span.count));
    out.model_prediction = storage;
  }
  return out;
}

}  // namespace residual_walk
}  // namespace dcurve
