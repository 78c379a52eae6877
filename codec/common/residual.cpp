#include "codec/common/residual.h"

#include <algorithm>

namespace dcurve {

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

}  // namespace dcurve
