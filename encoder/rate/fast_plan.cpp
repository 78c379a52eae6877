#include "encoder/rate/fast_plan.h"

#include <algorithm>
#include <cmath>

#include "codec/common/error.h"
#include "codec/common/fast_residual.h"
#include "codec/common/fast_traversal.h"
#include "codec/common/residual.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "encoder/parallel.h"
#include "encoder/rate/plan_steps.h"

namespace dcurve {

using namespace fast_residual;

namespace {

// What every chunk's plan reads.
struct FastInputs {
  const ResidualLayer* layer = nullptr;
  const std::vector<std::vector<float>>* frames = nullptr;
  const std::vector<int32_t>* model = nullptr;  // every frame's Model prediction, or null
  const FastTraversal* traversal = nullptr;
  double radius = 0;
  uint32_t V = 0;
};

// Estimated bits of one vertex's residuals as the fast coder spends them: an op byte for a
// vertex with any non-zero value, then each value's magnitude and sign.
int vertex_bits(const int64_t* r) {
  const int bits = residual_cost(r[0]) + residual_cost(r[1]) + residual_cost(r[2]);
  return bits == 0 ? 0 : bits + 4;
}

// Frame values snapped vertex by vertex against the kind byte's prediction (base: the dense
// base prediction; with the spatial flag, vertices in traversal order, each also predicted
// from the corrections e of the positions before it, kept in traversal order) into q;
// returns estimated bits.
int64_t snap_frame(const FastInputs& in, const float* x, const std::vector<AxisRun>& runs, uint8_t kind,
                   const int32_t* base, int32_t* q, int64_t* e) {
  const bool spatial = has_spatial(kind);
  int64_t bits = 0;
  for (uint32_t pos = 0; pos < in.V; ++pos) {
    const size_t i = size_t(spatial ? in.traversal->order[pos] : pos) * 3;
    int64_t p[3];
    for (int a = 0; a < 3; ++a) {
      p[a] = base[i + size_t(a)] + (spatial ? fast_spatial(*in.traversal, pos, e, a, is_smooth(kind)) : 0);
      q[i + size_t(a)] = int32_t(runs[i + size_t(a)].nearest);
    }
    snap_vertex(*in.layer, x + i, &runs[i], in.radius, 0.0, p, q + i);
    const int64_t r[3] = {q[i] - p[0], q[i + 1] - p[1], q[i + 2] - p[2]};
    for (int a = 0; a < 3; ++a) e[size_t(pos) * 3 + size_t(a)] = int64_t(q[i + size_t(a)]) - base[i + size_t(a)];
    bits += vertex_bits(r);
  }
  return bits;
}

// Kinds and grid values of one chunk's frames: per frame, the usable kind that costs least,
// one that reads no earlier frame wherever a seek would otherwise decode more than
// kMaxSeekFrames frames.
void plan_chunk(const FastInputs& in, ChunkSpan span, uint8_t* kinds, int32_t* q) {
  const size_t n = size_t(in.V) * 3;
  std::vector<int32_t> pred(n), trial(n);
  std::vector<int64_t> corrections(n);
  uint32_t seek = 0;  // frames a seek to the frame before decodes
  for (uint32_t k = 0; k < span.count; ++k) {
    const uint32_t f = span.first + k;
    const float* x = (*in.frames)[f].data();
    const std::vector<AxisRun> runs = axis_runs(*in.layer, x, in.V, in.radius);
    const int32_t* M = in.model ? in.model->data() + n * f : nullptr;
    int32_t* out = q + n * k;
    int64_t best = INT64_MAX;
    for (uint8_t base = 0; base < kFrameKindCount; ++base) {
      if (!kind_usable(base, k, M != nullptr)) continue;
      if (seek >= kMaxSeekFrames && frames_needed(FrameKind(base)) > 0) continue;
      predict_frame(FrameKind(base), k >= 1 ? out - n : nullptr, k >= 2 ? out - 2 * n : nullptr, M,
                    M && k >= 1 ? M - n : nullptr, n, pred.data());
      for (uint8_t kind : {base, uint8_t(base | kSpatialFlag), uint8_t(base | kSpatialFlag | kSmoothFlag)}) {
        const int64_t bits = snap_frame(in, x, runs, kind, pred.data(), trial.data(), corrections.data());
        if (bits < best) {
          best = bits;
          kinds[k] = kind;
          std::copy(trial.begin(), trial.end(), out);
        }
      }
    }
    seek = frames_needed(base_kind(kinds[k])) > 0 ? seek + 1 : 1;
  }
}

// The payload of chunk length K, planned chunk by chunk on `threads` threads; *kinds the
// frames' kind bytes.
std::vector<uint8_t> plan_and_encode(const Model& m, const FastInputs& in, uint32_t K, int threads,
                                     std::vector<uint8_t>* kinds) {
  const uint32_t F = m.meta.frame_count;
  const size_t n = size_t(in.V) * 3;
  std::vector<int32_t> q(n * F);
  kinds->assign(F, 0);
  parallel_for(chunk_count(F, K), threads, [&](size_t c) {
    const ChunkSpan span = chunk_span(F, K, uint32_t(c));
    plan_chunk(in, span, kinds->data() + span.first, q.data() + n * span.first);
  });
  return encode_fast_residuals(m, q, *kinds, K, in.model);
}
}  // namespace

std::vector<uint32_t> fast_chunk_candidates(uint32_t F) {
  const uint32_t limit = std::max<uint32_t>(4, F / 10);
  std::vector<uint32_t> out;
  for (uint32_t K = 4; K <= limit && K <= 64; K *= 2) out.push_back(std::min(K, F));
  if (out.empty() || F <= 4) out = {F};
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

uint32_t fast_seek_frames(const std::vector<uint8_t>& kinds, uint32_t K) {
  uint32_t most = 0, run = 0;
  for (size_t f = 0; f < kinds.size(); ++f) {
    const bool starts = f % K == 0 || frames_needed(base_kind(kinds[f])) == 0;
    run = starts ? 1 : run + 1;
    most = std::max(most, run);
  }
  return most;
}

bool encode_fast_layer(Model* m, const std::vector<std::vector<float>>& frames, const FastLayerOptions& options,
                       std::string* error, const std::vector<int32_t>* prediction) {
  std::vector<int32_t> model;
  if (!prediction && has_model_prediction(*m) && !model_grid_prediction(*m, UINT64_MAX, &model, error)) return false;
  FastInputs in;
  in.layer = &m->residual;
  in.frames = &frames;
  in.model = prediction ? prediction : model.empty() ? nullptr : &model;
  in.radius = options.snap_distance;
  in.V = m->meta.vertex_count;
  const FastTraversal traversal = fast_traversal(m->faces, in.V);
  in.traversal = &traversal;
  const std::vector<uint32_t> lengths =
      options.chunk_frames ? std::vector<uint32_t>{std::min(options.chunk_frames, m->meta.frame_count)}
                           : fast_chunk_candidates(m->meta.frame_count);
  std::vector<uint8_t> best, kinds;
  uint32_t best_K = 0;
  for (uint32_t K : lengths) {
    std::vector<uint8_t> payload = plan_and_encode(*m, in, K, options.threads, &kinds);
    if (payload.empty()) return fail(error, "internal error: the fast residual plan is invalid");
    if (fast_seek_frames(kinds, K) > kMaxSeekFrames) return fail(error, "internal error: a fast plan's seek is too long");
    // A longer chunk costs a seek more stream to read; it has to save more than 1 % to win.
    if (best.empty() || double(payload.size()) < 0.99 * double(best.size())) {
      best.swap(payload);
      best_K = K;
    }
  }
  m->residual.payload = std::move(best);
  m->residual.chunk_frames = best_K;
  return true;
}

}  // namespace dcurve
