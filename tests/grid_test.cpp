// The grid that carries the error guarantee and the snapping of grid values: rounding to
// the (refined) grid stays within the tolerance, a tolerance too small for the refined
// grid's int32 range falls back to the coarsest grid, the grid search finds the cheapest
// refinement, snapping finds the cheapest admissible grid point (as a search of every
// lattice point would) and among equally cheap ones keeps the one nearest the input; the
// plan's running entropy bound never shrinks and ends at the whole estimate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <random>

#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/plan_steps.h"
#include "encoder/rate/residual_plan.h"

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

// The residual layer alone, one coding order and no clusters, as the trial encode: what
// the grid changes most.
GridTrial residual_trial(const Model& model, double max_distance) {
  return [&model, max_distance](const ResidualLayer& grid, const Animation& part, size_t, int threads) -> size_t {
    Model trial = model;
    trial.meta.frame_count = uint32_t(part.frames.size());
    trial.residual = grid;
    std::vector<int32_t> q;
    if (!quantize_to_grid(part, grid, &q, nullptr)) return SIZE_MAX;
    ResidualPlanOptions po;
    po.gop_sizes = {8};
    po.cluster_layouts.clear();
    po.threads = threads;
    const PredictorPlan plan = choose_plan_and_grid(trial, part.frames, max_distance * (1.0 - 1e-6), &q, {}, po);
    return encode_residuals(trial, q, &plan).size();
  };
}

TEST(Grid, SlowSmoothMotionGetsAFinerGridAndNoiseTheCoarsest) {
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
  const GridChoice fine = choose_grid(slow, max_distance, 1, residual_trial(slow_model, max_distance));
  EXPECT_LT(fine.grid.step, coarse);
  EXPECT_TRUE(fine.whole);
  // Independent noise of many steps per vertex and frame: every value costs its magnitude.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-40 * coarse, 40 * coarse);
  Animation noisy;
  const Model noisy_model = sheet_model(16, 24, [&](uint32_t, double x, double y, std::vector<float>* xyz) {
    xyz->push_back(float(x + noise(rng)));
    xyz->push_back(float(y + noise(rng)));
    xyz->push_back(float(noise(rng)));
  }, &noisy);
  EXPECT_DOUBLE_EQ(choose_grid(noisy, max_distance, 1, residual_trial(noisy_model, max_distance)).grid.step, coarse);
}

// A trial cost with its minimum at refinement `target`, counting the trials.
// Trials run side by side: `tried` is shared.
GridTrial recording(double coarse, std::vector<double>* tried, std::function<size_t(double)> bytes) {
  auto lock = std::make_shared<std::mutex>();
  return [=](const ResidualLayer& grid, const Animation&, size_t, int) -> size_t {
    const double refinement = coarse / grid.step;
    {
      std::lock_guard<std::mutex> hold(*lock);
      tried->push_back(refinement);
    }
    return bytes(refinement);
  };
}

GridTrial valley(double coarse, double target, std::vector<double>* tried) {
  return recording(coarse, tried,
                   [=](double refinement) { return size_t(1000 + 100 * std::fabs(std::log2(refinement / target))); });
}

TEST(Grid, SearchFindsTheCheapestRefinementInFewTrials) {
  const Animation anim = random_animation(50, 40, 1.0, 3);
  const double max_distance = 1e-3, coarse = coarsest_step(max_distance);
  for (double target : {1.0, 1.5, 2.0, 3.0, 4.0, 8.0}) {
    std::vector<double> tried;
    const GridChoice c = choose_grid(anim, max_distance, 2, valley(coarse, target, &tried));
    EXPECT_NEAR(c.grid.step, coarse / target, 1e-12 * coarse) << "target " << target;
    EXPECT_TRUE(c.whole);
    // Two first trials, then the neighbours of the better, while the best moves.
    EXPECT_LE(tried.size(), target <= 3 ? 4u : target <= 4 ? 5u : 6u) << "target " << target;
  }
}

// Sizes need not be unimodal in the refinement (the neck scene: 3x best among 2x, 3x and 4x,
// 6x better still). A neighbour within 2 % of the best leads the search one step further;
// one 4 % worse does not.
TEST(Grid, SearchLooksPastANearlyAsGoodNeighbour) {
  const Animation anim = random_animation(50, 40, 1.0, 3);
  const double max_distance = 1e-3, coarse = coarsest_step(max_distance);
  for (size_t at_four : {1010u, 1040u}) {
    std::vector<double> tried;
    const std::map<double, size_t> sizes = {{1.0, 1300}, {1.5, 1200}, {2.0, 1100}, {3.0, 1000},
                                            {4.0, at_four}, {6.0, 900}, {8.0, 950}};
    const GridChoice c = choose_grid(anim, max_distance, 2, recording(coarse, &tried, [&](double r) {
      for (const auto& [refinement, bytes] : sizes)
        if (std::fabs(refinement - r) < 1e-9) return bytes;
      return size_t(99999);
    }));
    const double expected = at_four == 1010u ? 6.0 : 3.0;
    EXPECT_NEAR(c.grid.step, coarse / expected, 1e-12 * coarse) << at_four;
    EXPECT_LE(tried.size(), at_four == 1010u ? 6u : 4u) << at_four;
  }
}

// The bracket (effort 2) tries 3x and 8x and nothing else, wherever the cheapest lies, and
// keeps the smaller (the coarser of equals).
TEST(Grid, BracketTriesThreeAndEightTimesFinerOnly) {
  const Animation anim = random_animation(50, 40, 1.0, 3);
  const double max_distance = 1e-3, coarse = coarsest_step(max_distance);
  for (double target : {1.0, 3.0, 4.0, 6.0, 8.0}) {
    std::vector<double> tried;
    const GridChoice c = choose_grid(anim, max_distance, 2, valley(coarse, target, &tried), GridSearch::Bracket);
    std::sort(tried.begin(), tried.end());
    ASSERT_EQ(tried.size(), 2u) << "target " << target;
    EXPECT_NEAR(tried[0], 3.0, 1e-9);
    EXPECT_NEAR(tried[1], 8.0, 1e-9);
    const double expected = std::fabs(std::log2(target / 3.0)) <= std::fabs(std::log2(target / 8.0)) ? 3.0 : 8.0;
    EXPECT_NEAR(c.grid.step, coarse / expected, 1e-12 * coarse) << "target " << target;
    EXPECT_TRUE(c.whole);
  }
}

TEST(Grid, LargeAnimationsAreTriedOnAMiddleRunAndFailedTrialsKeepTheCoarsest) {
  const Animation anim = random_animation(20000, 40, 1.0, 4);  // 800k vertex-frames
  const double max_distance = 1e-3;
  std::vector<uint32_t> frames;
  const GridChoice c = choose_grid(anim, max_distance, 1, [&](const ResidualLayer&, const Animation& part, size_t, int) {
    frames.push_back(uint32_t(part.frames.size()));
    EXPECT_EQ(part.frames.front(), anim.frames[(40 - part.frames.size()) / 2]);
    return SIZE_MAX;
  });
  ASSERT_FALSE(frames.empty());
  EXPECT_LT(frames.front(), 40u);
  EXPECT_GE(frames.front(), 33u);
  EXPECT_FALSE(c.whole);
  EXPECT_DOUBLE_EQ(c.grid.step, coarsest_step(max_distance));
}

// The plan drops a candidate once its running bits exceed the best complete one's: sound
// only if the running figure never shrinks and ends at estimate_residual_bits' value. The
// plan ranks complete candidates by estimate(), which must equal that value exactly.
TEST(RunningBits, NeverShrinksAndEndsAtTheWholeListsEstimate) {
  std::mt19937 rng(7);
  std::geometric_distribution<int> magnitude(0.4);
  std::uniform_int_distribution<int> context(0, int(RunningBits::kContexts) - 1), coin(0, 1);
  for (size_t n : {1u, 17u, 3000u}) {
    std::vector<int64_t> residuals;
    std::vector<uint8_t> contexts;
    RunningBits running(n);
    running.reset();
    double previous = 0;
    for (size_t i = 0; i < n; ++i) {
      // Mostly small values, a few far beyond the clamp, both signs, skewed per context.
      const int c = context(rng);
      int64_t r = magnitude(rng) * (c % 3 + 1);
      if (i % 97 == 0) r = int64_t(1) << (20 + i % 20);
      if (coin(rng)) r = -r;
      residuals.push_back(r);
      contexts.push_back(uint8_t(c));
      running.add(size_t(c), r);
      ASSERT_GE(running.bits(), previous) << "after " << i + 1 << " residuals";
      previous = running.bits();
      // Every prefix's running figure is that prefix's own estimate.
      if (i % 250 == 0 || i + 1 == n) {
        ASSERT_NEAR(running.bits(), estimate_residual_bits(residuals, contexts), 1e-9 * (1 + running.bits()));
        ASSERT_EQ(running.estimate(), estimate_residual_bits(residuals, contexts));
      }
    }
    running.reset();
    EXPECT_EQ(running.bits(), 0.0);
  }
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

// Every lattice point of the box around the ball: the (score, distance) snap_vertex must reach.
void brute_force_snap(const ResidualLayer& layer, const float* x, double radius, double weight, const int64_t* pred,
                      const int32_t* start, double* best_score, double* best_d2) {
  const double r2 = radius * radius;
  auto eval = [&](const int64_t* k, double* sc, double* d2) {
    *d2 = 0;
    int bits = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = double(grid_to_model(layer, a, k[a])) - double(x[a]);
      *d2 += d * d;
      bits += residual_cost(k[a] - pred[a]);
    }
    *sc = bits + weight * *d2 / r2;
  };
  const int64_t s[3] = {start[0], start[1], start[2]};
  eval(s, best_score, best_d2);
  int64_t lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = int64_t(std::floor((double(x[a]) - radius - layer.origin[a]) / layer.step));
    hi[a] = int64_t(std::ceil((double(x[a]) + radius - layer.origin[a]) / layer.step));
  }
  int64_t k[3];
  for (k[0] = lo[0]; k[0] <= hi[0]; ++k[0])
    for (k[1] = lo[1]; k[1] <= hi[1]; ++k[1])
      for (k[2] = lo[2]; k[2] <= hi[2]; ++k[2]) {
        double sc, d2;
        eval(k, &sc, &d2);
        if (d2 <= r2 && (sc < *best_score || (sc == *best_score && d2 < *best_d2))) {
          *best_score = sc;
          *best_d2 = d2;
        }
      }
}

// Snaps qv and compares with the search of every lattice point: admissible, the same score
// and, among equal scores, the same distance.
::testing::AssertionResult snap_matches_search(const ResidualLayer& layer, const float* x, double radius,
                                               double weight, const int64_t* pred, int32_t* qv) {
  double want_score, want_d2;
  brute_force_snap(layer, x, radius, weight, pred, qv, &want_score, &want_d2);
  snap_vertex(layer, x, radius, weight, pred, qv);
  double got_d2 = 0;
  int bits = 0;
  for (int a = 0; a < 3; ++a) {
    const double d = double(grid_to_model(layer, a, qv[a])) - double(x[a]);
    got_d2 += d * d;
    bits += residual_cost(qv[a] - pred[a]);
  }
  const double got_score = bits + weight * got_d2 / (radius * radius);
  if (got_d2 > radius * radius) return ::testing::AssertionFailure() << "outside the ball: " << got_d2;
  if (got_score != want_score || got_d2 != want_d2)
    return ::testing::AssertionFailure() << "score " << got_score << " distance^2 " << got_d2 << ", the search found "
                                         << want_score << " and " << want_d2;
  return ::testing::AssertionSuccess();
}

TEST(Snap, FindsWhatASearchOfEveryLatticePointFinds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    ResidualLayer layer;
    layer.step = 1.0;
    layer.origin[0] = layer.origin[1] = layer.origin[2] = 0.0;
    const double radius = 0.8 + 6.0 * u(rng);  // refinements from the coarsest to about 8
    const double weight = trial % 3 == 0 ? 0.5 * u(rng) : 0.0;
    float x[3];
    int64_t pred[3];
    int32_t qv[3];
    const double spread = trial % 2 ? 3 * radius : 80.0;  // near and far predictions
    for (int a = 0; a < 3; ++a) {
      x[a] = float(100 + 20 * u(rng));
      pred[a] = int64_t(std::llround(x[a] + spread * (2 * u(rng) - 1)));
      qv[a] = int32_t(std::lround(x[a]));
    }
    ASSERT_TRUE(snap_matches_search(layer, x, radius, weight, pred, qv)) << "trial " << trial;
  }
}

// A grid finer than float32's resolution at the mesh's coordinates: several grid values decode
// to the same float, so distances repeat in runs, and snapping must still find the best point.
TEST(Snap, FindsTheBestPointWhereGridValuesDecodeToTheSameFloat) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    ResidualLayer layer;
    layer.step = 2e-6;  // float32's spacing near 100 is 7.6e-6
    layer.origin[0] = layer.origin[1] = layer.origin[2] = 100.0;
    const double radius = layer.step * (0.8 + 12.0 * u(rng));
    const double weight = trial % 3 == 0 ? 0.5 * u(rng) : 0.0;
    float x[3];
    int64_t pred[3];
    int32_t qv[3];
    for (int a = 0; a < 3; ++a) {
      const double g = 1000 + 50 * u(rng);  // in grid steps from the origin
      x[a] = float(layer.origin[a] + g * layer.step);
      pred[a] = int64_t(std::llround(g + 40 * (2 * u(rng) - 1)));
      // Start where the encoder does, on an admissible point: one decoding exactly to x.
      qv[a] = int32_t(std::lround(g)) - 8;
      while (grid_to_model(layer, a, qv[a]) < x[a]) ++qv[a];
      ASSERT_EQ(grid_to_model(layer, a, qv[a]), x[a]);
    }
    ASSERT_TRUE(snap_matches_search(layer, x, radius, weight, pred, qv)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace dcurve
