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
    const int32_t* model_frame = model_values(options, f, stride, ws);
    // Linear predictions are computed for the frame, V values per (candidate, axis) that uses
    // one (at linear_at[j * 3 + a]); the other kinds are read in place.
    std::array<uint32_t, kMaxCandidates * 3> linear_at{};
    uint32_t linears = 0;
    for (uint32_t j = 0; j < K; ++j)
      for (int a = 0; a < 3; ++a)
        if (fp.candidates[j][size_t(a)].kind == PredictorKind::Linear) linear_at[j * 3 + uint32_t(a)] = linears++;
    base.resize(size_t(linears) * V);
    for (uint32_t j = 0; j < K; ++j)
      for (int a = 0; a < 3; ++a)
        if (fp.candidates[j][size_t(a)].kind == PredictorKind::Linear)
          base_prediction(fp.candidates[j][size_t(a)], f, a, V, q, options, &base[linear_at[j * 3 + uint32_t(a)] * size_t(V)]);
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
      const uint32_t* linear_j = &linear_at[j * 3];
      const int32_t* model_f = model_frame;
      auto base_of = [&](uint32_t u, int a) -> int64_t {
        switch (choice[a].kind) {
          case PredictorKind::None: return 0;
          case PredictorKind::Reference: return ref[a][size_t(u) * 3 + size_t(a)];
          case PredictorKind::Motion: return motion_prediction(rows[a], a, centre + 3 * a, ref[a] + size_t(u) * 3);
          case PredictorKind::Model: return model_f[size_t(u) * 3 + size_t(a)];
          case PredictorKind::Linear: break;
        }
        return base[linear_j[a] * size_t(V) + u];
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

// CRC-32C of the values as little-endian int32: a stream that still decodes to in-range
// values against another prediction (a damaged model) is caught.
inline uint32_t values_checksum(const int32_t* q, size_t count) {
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
