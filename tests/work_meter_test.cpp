// The encode's progress: the WorkMeter's fraction against its forecast, and what a real
// encode reports through EncodeOptions::progress (frames planned, never backwards, ending at
// 1, the file unchanged).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "encoder/encoder.h"
#include "encoder/work_meter.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

TEST(WorkMeter, CountsFramesAgainstTheForecastStageByStage) {
  std::vector<double> seen;
  WorkMeter meter([&](double f) { seen.push_back(f); });
  meter.forecast({10, 30});
  meter.add(5);
  EXPECT_DOUBLE_EQ(seen.back(), 5.0 / 40);
  // A stage that plans more than its forecast holds at the stage's end...
  meter.add(20);
  EXPECT_DOUBLE_EQ(seen.back(), 10.0 / 40);
  meter.end_stage();
  EXPECT_DOUBLE_EQ(seen.back(), 10.0 / 40);
  // ...and the next counts from there.
  meter.add(15);
  EXPECT_DOUBLE_EQ(seen.back(), 25.0 / 40);
  EXPECT_EQ(meter.frames_planned(), 40u);
  // A stage that planned less than its forecast is done when it ends.
  meter.end_stage();
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
}

TEST(WorkMeter, NeverGoesBackWhenTheForecastGrows) {
  std::vector<double> seen;
  WorkMeter meter([&](double f) { seen.push_back(f); });
  meter.forecast({10});
  meter.add(8);
  meter.forecast({10, 90});  // more work found: the fraction would drop to 0.08
  meter.add(1);
  for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]) << i;
  EXPECT_DOUBLE_EQ(seen.back(), 0.8);
}

TEST(EncodeProgress, CountsPlannedFramesUpToOneAndLeavesTheFileAlone) {
  const Animation anim = simulate_builtin("cantilever", 12);
  EncodeOptions o;
  std::vector<double> seen;
  o.progress = [&](double f) { seen.push_back(f); };
  const std::vector<uint8_t> with = encoded(anim, o);
  ASSERT_FALSE(seen.empty());
  for (size_t i = 1; i < seen.size(); ++i) ASSERT_GE(seen[i], seen[i - 1]) << i;
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  // One step per frame planned, not a few jumps between stages: 12 frames in several
  // coding orders and layouts, on two grids.
  size_t below_half = 0;
  for (double f : seen) below_half += f < 0.5;
  EXPECT_GT(below_half, 24u);
  o.progress = nullptr;
  EXPECT_EQ(encoded(anim, o), with);
}

}  // namespace
}  // namespace dcurve::test
