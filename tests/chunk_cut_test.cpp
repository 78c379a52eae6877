// A whole-clip plan cut into chunks (encoder/rate/chunk_cut.h): every chunk's plan is valid
// and codes the same grid values bit-exactly; predictors that reach only frames of their
// chunk survive, the others become spatial-only.
#include <gtest/gtest.h>

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/metrics.h"
#include "encoder/rate/chunk_cut.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/residual_plan.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

bool reaches_inside(const PredictorChoice& c, ChunkSpan span) {
  auto in = [&](uint32_t r) { return r >= span.first && r < span.first + span.count; };
  const bool refs = !has_reference(c.kind) || (in(c.r0) && (c.kind != PredictorKind::Linear || in(c.r1)));
  return refs && (!uses_geometry(c.spatial) || in(c.g));
}

// A built-in scene on its 3x refined grid, with its rounded grid values (empty on failure).
struct GridClip {
  Animation anim;
  double max_distance = 0;
  Model model;
  std::vector<int32_t> q;
};
GridClip grid_clip(const std::string& scene, uint32_t frames) {
  GridClip c;
  c.anim = simulate_builtin(scene, frames);
  const double L = bbox_diagonal(c.anim.frames[0]);
  c.max_distance = 1e-3 * L;
  c.model.meta = {c.anim.vertex_count, uint32_t(c.anim.frames.size()), 30.0, 1e-3, L, ""};
  c.model.faces = c.anim.faces;
  c.model.curves = singleton_curves(c.anim.vertex_count);
  c.model.residual = make_grid(c.anim, c.max_distance, 3.0);
  if (!quantize_to_grid(c.anim, c.model.residual, &c.q, nullptr)) c.q.clear();
  return c;
}

TEST(ChunkCut, CutPlansAreValidAndCodeTheSameValues) {
  const GridClip clip = grid_clip("cantilever", 20);
  ASSERT_FALSE(clip.q.empty());
  const Animation& anim = clip.anim;
  const Model& m = clip.model;
  const double max_distance = clip.max_distance;
  std::vector<int32_t> q = clip.q;
  std::string err;
  const PredictorPlan whole = choose_plan_and_grid(m, anim.frames, max_distance, &q);
  const uint32_t F = m.meta.frame_count;
  for (uint32_t K : {1u, 3u, 8u, 19u}) {
    SCOPED_TRACE("K " + std::to_string(K));
    const ResidualPlan cut = cut_into_chunks(whole, F, K, false);
    ASSERT_EQ(cut.chunks.size(), chunk_count(F, K));
    size_t kept = 0, replaced = 0;
    for (uint32_t c = 0; c < cut.chunks.size(); ++c) {
      const ChunkSpan span = chunk_span(F, K, c);
      ASSERT_TRUE(plan_is_valid(cut.chunks[c], span.count, m.meta.vertex_count, {})) << "chunk " << c;
      for (uint32_t f = span.first; f < span.first + span.count; ++f)
        for (size_t j = 0; j < whole.frames[f].candidates.size(); ++j)
          for (int a = 0; a < 3; ++a) {
            const PredictorChoice& before = whole.frames[f].candidates[j][size_t(a)];
            const PredictorChoice& after = cut.chunks[c].frames[f - span.first].candidates[j][size_t(a)];
            if (reaches_inside(before, span)) {
              ++kept;
              EXPECT_EQ(after.kind, before.kind);
              EXPECT_EQ(after.spatial, before.spatial);
              if (has_reference(before.kind)) {
                EXPECT_EQ(after.r0 + span.first, before.r0);
              }
            } else {
              ++replaced;
              EXPECT_TRUE(after.kind == before.kind || after.kind == PredictorKind::None) << "frame " << f;
            }
          }
    }
    EXPECT_GT(kept, 0u);
    if (K < F) {
      EXPECT_GT(replaced, 0u);  // a chunk's first frame had a reference before it
    }
    Model chunked = m;
    chunked.residual.chunk_frames = K;
    chunked.residual.payload = encode_residuals(chunked, q, cut, {});
    ASSERT_FALSE(chunked.residual.payload.empty());
    std::vector<int32_t> decoded;
    ASSERT_TRUE(decode_residuals(chunked, &decoded, &err)) << err;
    EXPECT_EQ(decoded, q);
  }
}

// Choices of `plan` that use a geometry frame; each must name `first` (the plan's first
// coded frame), and that frame itself names none.
size_t geometry_choices_name(const PredictorPlan& plan, uint32_t first) {
  size_t used = 0;
  for (uint32_t f = 0; f < plan.frames.size(); ++f)
    for (const auto& candidate : plan.frames[f].candidates)
      for (const PredictorChoice& c : candidate) {
        if (!uses_geometry(c.spatial)) continue;
        ++used;
        EXPECT_NE(f, first);
        EXPECT_EQ(c.g, first) << "frame " << f;
      }
  return used;
}

// A decoder solves a weight table per geometry frame: the planner names one per chunk, its
// first coded frame, and a cut chunk names its own first coded frame in place of the clip's.
TEST(ChunkCut, OneGeometryFramePerChunk) {
  const GridClip clip = grid_clip("sheet", 24);
  ASSERT_FALSE(clip.q.empty());
  std::vector<int32_t> q = clip.q;
  const PredictorPlan whole = choose_plan_and_grid(clip.model, clip.anim.frames, clip.max_distance, &q);
  ASSERT_GT(geometry_choices_name(whole, whole.order[0]), 3u);  // the test means something
  const uint32_t F = clip.model.meta.frame_count;
  for (uint32_t K : {8u, 10u}) {
    const ResidualPlan cut = cut_into_chunks(whole, F, K, false);
    size_t used_after_first = 0;  // where the clip's first frame lies outside the chunk
    for (size_t c = 0; c < cut.chunks.size(); ++c) {
      const size_t used = geometry_choices_name(cut.chunks[c], cut.chunks[c].order[0]);
      if (c > 0) used_after_first += used;
    }
    EXPECT_GT(used_after_first, 0u) << "K " << K;
  }
}

// Geometry frames named by any choice of `plan`.
std::set<uint32_t> geometry_frames(const PredictorPlan& plan) {
  std::set<uint32_t> out;
  for (const FramePredictors& fp : plan.frames)
    for (const auto& candidate : fp.candidates)
      for (const PredictorChoice& c : candidate)
        if (uses_geometry(c.spatial)) out.insert(c.g);
  return out;
}

// A table per frame when asked for; tried (--effort 2 and 3), it is kept only when it codes the
// chunk smaller than one table by more than kPerFrameGeometryGain.
TEST(ChunkCut, PerFrameGeometryIsAskedForOrMustPay) {
  const GridClip clip = grid_clip("sheet", 24);
  ASSERT_FALSE(clip.q.empty());
  auto plan_with = [&](bool per_frame, bool try_per_frame, size_t* bytes) {
    ResidualPlanOptions po;
    po.geometry_per_frame = per_frame;
    po.try_geometry_per_frame = try_per_frame;
    std::vector<int32_t> q = clip.q;
    PredictorPlan plan = choose_plan_and_grid(clip.model, clip.anim.frames, clip.max_distance, &q, {}, po);
    *bytes = encode_residuals(clip.model, q, &plan, {}).size();
    return plan;
  };
  size_t one_bytes = 0, per_frame_bytes = 0, tried_bytes = 0;
  const PredictorPlan one = plan_with(false, false, &one_bytes);
  const PredictorPlan per_frame = plan_with(true, false, &per_frame_bytes);
  const PredictorPlan tried = plan_with(false, true, &tried_bytes);
  EXPECT_EQ(geometry_frames(one).size(), 1u);
  EXPECT_GT(geometry_frames(per_frame).size(), 2u);
  if (geometry_frames(tried).size() > 1) EXPECT_LT(double(tried_bytes), double(one_bytes) * (1 - kPerFrameGeometryGain));
  else EXPECT_EQ(tried_bytes, one_bytes);
}

// A plan narrowed to the one that won keeps its geometry rule and tries no other: an encode
// that follows a trial of part of the clip plans the rule the trial kept.
TEST(ChunkCut, NarrowedOptionsKeepTheWinnersGeometryRule) {
  const GridClip clip = grid_clip("sheet", 24);
  ASSERT_FALSE(clip.q.empty());
  ResidualPlanOptions tries;
  tries.try_geometry_per_frame = true;
  for (bool per_frame : {false, true}) {
    ResidualPlanOptions po;
    po.geometry_per_frame = per_frame;
    std::vector<int32_t> q = clip.q;
    const PredictorPlan won = choose_plan_and_grid(clip.model, clip.anim.frames, clip.max_distance, &q, {}, po);
    ASSERT_EQ(geometry_per_frame(won), per_frame);
    const ResidualPlanOptions narrow = narrow_to_plan(tries, won);
    EXPECT_EQ(narrow.geometry_per_frame, per_frame);
    EXPECT_FALSE(narrow.try_geometry_per_frame);
  }
}

}  // namespace
}  // namespace dcurve::test
