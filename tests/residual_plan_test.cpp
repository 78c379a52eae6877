// Planning options narrowed to a plan's own choices (encoder/rate/residual_plan.h): planning
// again with them tries one coding order and at most one layout, and gives the same plan.
// The walk over coding orders keeps the smallest of them where sizes fall steadily, and
// plans fewer than all.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "encoder/metrics.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/residual_plan.h"
#include "encoder/work_meter.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

// Both layout orders, so that narrowing to a fixed position of the list cannot pass.
TEST(ResidualPlan, NarrowedToItsChoicesPlansTheSamePlanAgain) {
  const Animation anim = simulate_builtin("cantilever", 20);
  const double max_distance = 1e-3 * bbox_diagonal(anim.frames[0]);
  ResidualPlanOptions reversed;
  std::reverse(reversed.cluster_layouts.begin(), reversed.cluster_layouts.end());
  for (double refinement : {1.0, 6.0})
    for (const ResidualPlanOptions& all : {ResidualPlanOptions(), reversed}) {
      SCOPED_TRACE("refinement " + std::to_string(refinement) + ", first layout " +
                   std::to_string(all.cluster_layouts[0].cluster_size));
      Model m;
      m.meta = {anim.vertex_count, uint32_t(anim.frames.size()), 30.0, 1e-3, bbox_diagonal(anim.frames[0]), ""};
      m.faces = anim.faces;
      m.curves = singleton_curves(anim.vertex_count);
      m.residual = make_grid(anim, max_distance, refinement);
      std::vector<int32_t> q;
      std::string err;
      ASSERT_TRUE(quantize_to_grid(anim, m.residual, &q, &err)) << err;
      std::vector<int32_t> again = q;
      const PredictorPlan won = choose_plan_and_grid(m, anim.frames, max_distance, &q, {}, all);
      const ResidualPlanOptions narrow = narrow_to_plan(all, won);
      ASSERT_EQ(narrow.gop_sizes.size(), 1u);
      ASSERT_LE(narrow.cluster_layouts.size(), 1u);
      if (narrow.cluster_layouts.empty()) EXPECT_EQ(won.cluster_size, UINT32_MAX);
      else EXPECT_EQ(narrow.cluster_layouts[0].cluster_size, won.cluster_size);
      const PredictorPlan replanned = choose_plan_and_grid(m, anim.frames, max_distance, &again, {}, narrow);
      EXPECT_EQ(replanned.order, won.order);
      EXPECT_EQ(replanned.cluster_size, won.cluster_size);
      EXPECT_EQ(again, q);
      EXPECT_EQ(encode_residuals(m, again, &replanned, {}), encode_residuals(m, q, &won, {}));
    }
}

// Each order planned alone gives its size; the walk must pick the smallest of them on these
// clips (their sizes fall or rise steadily) and plan fewer frames than all five orders would.
TEST(ResidualPlan, OrderWalkKeepsTheSmallestOrderAndSkipsSome) {
  for (const char* scene : {"cantilever", "rope-small"}) {
    SCOPED_TRACE(scene);
    const Animation anim = simulate_builtin(scene, 40);
    const double max_distance = 1e-3 * bbox_diagonal(anim.frames[0]);
    Model m;
    m.meta = {anim.vertex_count, uint32_t(anim.frames.size()), 30.0, 1e-3, bbox_diagonal(anim.frames[0]), ""};
    m.faces = anim.faces;
    m.curves = singleton_curves(anim.vertex_count);
    m.residual = make_grid(anim, max_distance, 3.0);
    std::vector<int32_t> rounded;
    std::string err;
    ASSERT_TRUE(quantize_to_grid(anim, m.residual, &rounded, &err)) << err;
    ResidualPlanOptions all;
    all.cluster_layouts.clear();  // the orders alone
    size_t smallest = SIZE_MAX;
    std::vector<uint32_t> smallest_order;
    for (uint32_t gop : all.gop_sizes) {
      ResidualPlanOptions one = all;
      one.gop_sizes = {gop};
      std::vector<int32_t> q = rounded;
      const PredictorPlan plan = choose_plan_and_grid(m, anim.frames, max_distance, &q, {}, one);
      const size_t bytes = encode_residuals(m, q, &plan, {}).size();
      if (bytes < smallest) {
        smallest = bytes;
        smallest_order = plan.order;
      }
    }
    WorkMeter meter(nullptr);
    all.meter = &meter;
    std::vector<int32_t> q = rounded;
    const PredictorPlan walked = choose_plan_and_grid(m, anim.frames, max_distance, &q, {}, all);
    EXPECT_EQ(walked.order, smallest_order);
    EXPECT_EQ(encode_residuals(m, q, &walked, {}).size(), smallest);
    EXPECT_LT(meter.frames_planned(), all.gop_sizes.size() * anim.frames.size());
    EXPECT_GE(meter.frames_planned(), 2 * anim.frames.size());
  }
}

}  // namespace
}  // namespace dcurve::test
