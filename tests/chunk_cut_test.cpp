// A whole-clip plan cut into chunks (encoder/rate/chunk_cut.h): every chunk's plan is valid
// and codes the same grid values bit-exactly; predictors that reach only frames of their
// chunk survive, the others become spatial-only.
#include <gtest/gtest.h>

#include <cstdint>
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

TEST(ChunkCut, CutPlansAreValidAndCodeTheSameValues) {
  const Animation anim = simulate_builtin("cantilever", 20);
  const double max_distance = 1e-3 * bbox_diagonal(anim.frames[0]);
  Model m;
  m.meta = {anim.vertex_count, uint32_t(anim.frames.size()), 30.0, 1e-3, bbox_diagonal(anim.frames[0]), ""};
  m.faces = anim.faces;
  m.curves = singleton_curves(anim.vertex_count);
  m.residual = make_grid(anim, max_distance, 3.0);
  std::vector<int32_t> q;
  std::string err;
  ASSERT_TRUE(quantize_to_grid(anim, m.residual, &q, &err)) << err;
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
              if (has_reference(before.kind)) EXPECT_EQ(after.r0 + span.first, before.r0);
            } else {
              ++replaced;
              EXPECT_TRUE(after.kind == before.kind || after.kind == PredictorKind::None) << "frame " << f;
            }
          }
    }
    EXPECT_GT(kept, 0u);
    if (K < F) EXPECT_GT(replaced, 0u);  // a chunk's first frame had a reference before it
    Model chunked = m;
    chunked.residual.chunk_frames = K;
    chunked.residual.payload = encode_residuals(chunked, q, cut, {});
    ASSERT_FALSE(chunked.residual.payload.empty());
    std::vector<int32_t> decoded;
    ASSERT_TRUE(decode_residuals(chunked, &decoded, &err)) << err;
    EXPECT_EQ(decoded, q);
  }
}

}  // namespace
}  // namespace dcurve::test
