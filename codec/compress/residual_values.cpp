#include "codec/compress/residual_values.h"

#include "codec/common/residual_walk.h"

namespace dcurve {
namespace {

using residual_walk::options_for_chunk;
using residual_walk::walk_frames;

// The coder walk_frames drives to record the residuals instead of coding them.
struct ResidualRecorder {
  std::vector<int64_t>* out;
  bool residual(int, int, int64_t* r) {
    out->push_back(*r);
    return true;
  }
  bool zero_block(int, bool*) { return true; }
  bool index(uint32_t, uint32_t, uint32_t*) { return true; }
  bool row(int, const MotionRow&, MotionRow*) { return true; }
};

}  // namespace

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
