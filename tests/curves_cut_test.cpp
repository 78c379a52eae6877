// cut_to_target's sliding-window dynamic program against a plain O(n * target) one: same
// optimal cost, pieces within the target, vertex order kept.
#include <gtest/gtest.h>

#include <cmath>

#include "encoder/curves/cut_to_target.h"
#include "encoder/curves/link_paths.h"

namespace dcurve {
namespace {

using curves_detail::bend_cost;
using curves_detail::kShortCurvePenalty;

// A deterministic wiggly planar walk: mostly gentle turns, now and then a sharp one.
std::vector<float> walk(uint32_t n, uint32_t seed) {
  std::vector<float> xyz;
  double x = 0, y = 0, heading = 0;
  uint32_t state = seed;
  for (uint32_t i = 0; i < n; ++i) {
    xyz.insert(xyz.end(), {float(x), float(y), 0.f});
    state = state * 1664525u + 1013904223u;
    const double r = (state >> 8) / double(1u << 24);
    heading += r < 0.1 ? 2.5 * (r - 0.05) / 0.05 : 0.3 * (r - 0.55);
    x += std::cos(heading);
    y += std::sin(heading);
  }
  return xyz;
}

double piece_cost(const std::vector<float>& xyz, const uint32_t* v, size_t n, double w) {
  double cost = 1.0 + (n < 4 ? kShortCurvePenalty : 0.0);
  for (size_t i = 1; i + 1 < n; ++i) cost += bend_cost(xyz, v[i - 1], v[i], v[i + 1], w);
  return cost;
}

double brute_force_optimum(const std::vector<float>& xyz, const std::vector<uint32_t>& v, uint32_t target, double w) {
  std::vector<double> best(v.size() + 1, HUGE_VAL);
  best[0] = 0.0;
  for (size_t j = 1; j <= v.size(); ++j)
    for (size_t i = j > target ? j - target : 0; i < j; ++i)
      best[j] = std::min(best[j], best[i] + piece_cost(xyz, v.data() + i, j - i, w));
  return best.back();
}

TEST(CurvesCut, SlidingWindowMatchesBruteForce) {
  for (uint32_t seed : {1u, 7u, 42u}) {
    const uint32_t n = 150;
    const std::vector<float> xyz = walk(n, seed);
    Curves runs;
    for (uint32_t i = 0; i < n; ++i) runs.vertices.push_back(i);
    runs.offsets = {0, n};
    runs.closed = {0};
    for (uint32_t target : {2u, 3u, 4u, 5u, 9u, 40u, 1000u})
      for (double w : {0.0, 0.3, 1.0}) {
        const Curves cut = curves_detail::cut_to_target(runs, xyz, target, w);
        EXPECT_EQ(cut.vertices, runs.vertices);
        double total = 0.0;
        for (uint32_t c = 0; c < cut.curve_count(); ++c) {
          const uint32_t size = cut.offsets[c + 1] - cut.offsets[c];
          EXPECT_LE(size, target);
          EXPECT_FALSE(cut.closed[c]);
          total += piece_cost(xyz, cut.vertices.data() + cut.offsets[c], size, w);
        }
        EXPECT_NEAR(total, brute_force_optimum(xyz, runs.vertices, target, w), 1e-9)
            << "seed " << seed << " target " << target << " weight " << w;
      }
  }
}

TEST(CurvesCut, ClosedRunsStayClosedWhenTheyFitAndOpenAtTheSharpestBend) {
  // A square ring of 4 x 5 points: its corners are the only bends.
  std::vector<float> xyz;
  const int corner[4][2] = {{0, 0}, {5, 0}, {5, 5}, {0, 5}};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < 5; ++k) {
      const int* a = corner[side];
      const int* b = corner[(side + 1) % 4];
      xyz.insert(xyz.end(), {float(a[0] + (b[0] - a[0]) * k / 5.0), float(a[1] + (b[1] - a[1]) * k / 5.0), 0.f});
    }
  Curves ring;
  for (uint32_t i = 0; i < 20; ++i) ring.vertices.push_back((i + 2) % 20);  // start mid-side
  ring.offsets = {0, 20};
  ring.closed = {1};
  const Curves kept = curves_detail::cut_to_target(ring, xyz, 20, 0.3);
  EXPECT_EQ(kept.closed, std::vector<uint8_t>({1}));
  EXPECT_EQ(kept.vertices, ring.vertices);
  const Curves opened = curves_detail::cut_to_target(ring, xyz, 10, 0.3);
  ASSERT_GE(opened.curve_count(), 2u);
  // Every piece starts at a corner (ids 0, 5, 10, 15): the cuts remove the right angles.
  for (uint32_t c = 0; c < opened.curve_count(); ++c) {
    EXPECT_EQ(opened.vertices[opened.offsets[c]] % 5, 0u) << "piece " << c;
    EXPECT_FALSE(opened.closed[c]);
  }
}

}  // namespace
}  // namespace dcurve
