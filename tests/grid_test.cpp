// The grid that carries the error guarantee and the snapping of grid values: rounding to
// the (refined) grid stays within the tolerance, a tolerance too small for the refined
// grid's int32 range falls back to the coarsest grid, and among equally cheap admissible
// grid points snapping keeps the one nearest the input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/residual.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/plan_steps.h"

namespace dcurve {
namespace {

Animation random_animation(uint32_t vertices, uint32_t frames, double extent, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  Animation anim;
  anim.vertex_count = vertices;
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t i = 0; i < vertices * 3; ++i) xyz.push_back(float(u(rng)));
    anim.frames.push_back(xyz);
  }
  return anim;
}

double coarsest_step(double max_distance) { return 2.0 * max_distance / std::sqrt(3.0) * (1.0 - 1e-3); }

TEST(Grid, RefinedGridRoundsWithinTheBound) {
  const Animation anim = random_animation(200, 3, 1.0, 7);
  const double max_distance = 1e-3;
  const ResidualLayer grid = make_grid(anim, max_distance, 1.5);
  EXPECT_DOUBLE_EQ(grid.step, coarsest_step(max_distance) / 1.5);
  std::vector<int32_t> q;
  std::string error;
  ASSERT_TRUE(quantize_to_grid(anim, grid, &q, &error)) << error;
  const size_t n = size_t(anim.vertex_count) * 3;
  for (size_t f = 0; f < anim.frames.size(); ++f)
    for (size_t v = 0; v < anim.vertex_count; ++v) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) {
        const double d = double(grid_to_model(grid, a, q[f * n + v * 3 + size_t(a)])) -
                         double(anim.frames[f][v * 3 + size_t(a)]);
        d2 += d * d;
      }
      EXPECT_LE(std::sqrt(d2), max_distance) << "frame " << f << " vertex " << v;
    }
}

TEST(Grid, TinyToleranceKeepsTheCoarsestGridWithinInt32) {
  // An extent of 10400 at 1e-5 is 9.0e8 coarsest steps, within quantize_to_grid's range
  // (2^30); the refined grid would need 1.35e9.
  Animation anim;
  anim.vertex_count = 2;
  anim.frames.push_back({0.0f, 0.0f, 0.0f, 10400.0f, 10400.0f, 10400.0f});
  const double max_distance = 1e-5;
  const ResidualLayer grid = make_grid(anim, max_distance, 1.5);
  EXPECT_DOUBLE_EQ(grid.step, coarsest_step(max_distance));
  std::vector<int32_t> q;
  std::string error;
  EXPECT_TRUE(quantize_to_grid(anim, grid, &q, &error)) << error;
}

// A sheet of side x side vertices; frame f is `pose(f, x, y, xyz)`.
template <class Pose>
Model sheet_model(uint32_t side, uint32_t frames, Pose pose, Animation* anim) {
  anim->vertex_count = side * side;
  for (uint32_t i = 0; i + 1 < side; ++i)
    for (uint32_t j = 0; j + 1 < side; ++j) {
      const uint32_t a = i * side + j, b = a + 1, c = a + side, d = c + 1;
      anim->faces.insert(anim->faces.end(), {a, b, d, a, d, c});
    }
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t i = 0; i < side; ++i)
      for (uint32_t j = 0; j < side; ++j) pose(f, double(j) / (side - 1), double(i) / (side - 1), &xyz);
    anim->frames.push_back(xyz);
  }
  Model m;
  m.meta.vertex_count = anim->vertex_count;
  m.meta.frame_count = frames;
  m.faces = anim->faces;
  return m;
}

TEST(Grid, SlowSmoothMotionGetsTheFinerGridAndNoiseTheCoarsest) {
  const double max_distance = 1e-3 * std::sqrt(2.0);
  const double coarse = coarsest_step(max_distance);
  // Drifts a third of a coarsest step per frame, slowly turning: rounding drives the cost.
  Animation slow;
  const Model slow_model = sheet_model(16, 24, [&](uint32_t f, double x, double y, std::vector<float>* xyz) {
    const double ang = 0.002 * f;
    xyz->push_back(float(std::cos(ang) * x - std::sin(ang) * y + f * coarse / 3));
    xyz->push_back(float(std::sin(ang) * x + std::cos(ang) * y + f * coarse / 5));
    xyz->push_back(float(0.05 * x * y));
  }, &slow);
  EXPECT_LT(choose_grid(slow_model, slow, max_distance, 1).step, coarse);
  // Independent noise of many steps per vertex and frame: every value costs its magnitude.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-40 * coarse, 40 * coarse);
  Animation noisy;
  const Model noisy_model = sheet_model(16, 24, [&](uint32_t, double x, double y, std::vector<float>* xyz) {
    xyz->push_back(float(x + noise(rng)));
    xyz->push_back(float(y + noise(rng)));
    xyz->push_back(float(noise(rng)));
  }, &noisy);
  EXPECT_DOUBLE_EQ(choose_grid(noisy_model, noisy, max_distance, 1).step, coarse);
}

TEST(Snap, EquallyCheapPointsKeepTheNearest) {
  ResidualLayer layer;
  layer.step = 1.0;
  const float x[3] = {0.3f, 0.0f, 0.0f};
  const double radius = 0.75;  // admits (0,0,0) at 0.3 and (1,0,0) at 0.7, nothing else
  const int64_t pred[3] = {5, 0, 0};  // both cost one exponent-2 residual
  ASSERT_EQ(residual_cost(0 - 5), residual_cost(1 - 5));
  int32_t qv[3] = {1, 0, 0};  // starts on the farther point
  snap_vertex(layer, x, radius, 0.0, pred, qv);
  EXPECT_EQ(qv[0], 0);
  EXPECT_EQ(qv[1], 0);
  EXPECT_EQ(qv[2], 0);
}

TEST(Snap, ChoosesTheNearestOfTheCheapestAdmissiblePoints) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3, 3);
  ResidualLayer layer;
  layer.step = 1.0;
  for (int trial = 0; trial < 500; ++trial) {
    const float x[3] = {float(u(rng)), float(u(rng)), float(u(rng))};
    const double radius = 1.3;
    const int64_t pred[3] = {std::lround(u(rng) * 2), std::lround(u(rng) * 2), std::lround(u(rng) * 2)};
    int32_t qv[3];
    for (int a = 0; a < 3; ++a) qv[a] = int32_t(std::lround(x[a]));
    snap_vertex(layer, x, radius, 0.0, pred, qv);
    // Brute force over the points around x.
    int best_cost = INT32_MAX;
    double best_d2 = HUGE_VAL;
    for (int i = -3; i <= 3; ++i)
      for (int j = -3; j <= 3; ++j)
        for (int k = -3; k <= 3; ++k) {
          const int64_t p[3] = {std::lround(x[0]) + i, std::lround(x[1]) + j, std::lround(x[2]) + k};
          double d2 = 0;
          for (int a = 0; a < 3; ++a) d2 += (double(p[a]) - double(x[a])) * (double(p[a]) - double(x[a]));
          if (d2 > radius * radius) continue;
          const int cost = residual_cost(p[0] - pred[0]) + residual_cost(p[1] - pred[1]) + residual_cost(p[2] - pred[2]);
          if (cost < best_cost || (cost == best_cost && d2 < best_d2)) {
            best_cost = cost;
            best_d2 = d2;
          }
        }
    double d2 = 0;
    for (int a = 0; a < 3; ++a) d2 += (double(qv[a]) - double(x[a])) * (double(qv[a]) - double(x[a]));
    const int cost = residual_cost(qv[0] - pred[0]) + residual_cost(qv[1] - pred[1]) + residual_cost(qv[2] - pred[2]);
    EXPECT_EQ(cost, best_cost) << "trial " << trial;
    EXPECT_NEAR(d2, best_d2, 1e-9) << "trial " << trial;
  }
}

}  // namespace
}  // namespace dcurve
