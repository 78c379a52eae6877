// Physical behaviour of the XPBD simulator on small versions of the built-in scenes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "encoder/sim/scene.h"
#include "encoder/sim/simulation.h"

namespace dcurve {
namespace {

Scene builtin(const std::string& name) {
  Scene s;
  std::string err;
  EXPECT_TRUE(builtin_scene(name, &s, &err)) << err;
  return s;
}

// The cantilever at test size: half the grid resolution of the built-in scene.
Scene small_bar() {
  Scene s = builtin("cantilever");
  s.generator["divisions"] = {10, 2, 2};
  s.tet_max_volume = 1e-4;
  return s;
}

// The rope at test size: shorter, coarser, same material and section.
Scene small_rope() {
  Scene s = builtin("rope-small");
  s.generator["size"] = {0.64, 0.08, 0.08};
  s.generator["divisions"] = {16, 2, 2};
  s.mesh_translate = {0.32, 0, 0};
  s.tet_max_volume = 1e-4;
  return s;
}

// Mean displacement of the free end (the surface vertices farthest along +x) from rest.
double tip_sag(const SceneSimulation& sim) {
  const auto& x = sim.solver().positions();
  const auto& rest = sim.solver().rest_positions();
  double xmax = -1e30;
  for (uint32_t i = 0; i < sim.surface_vertex_count(); ++i) xmax = std::max(xmax, rest[i].x());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (uint32_t i = 0; i < sim.surface_vertex_count(); ++i)
    if (rest[i].x() > xmax - 1e-9) {
      sum += x[i] - rest[i];
      ++n;
    }
  return (sum / n).norm();
}

// Runs until the kinetic energy has fallen below `settled` J (or `max_frames`) and returns
// the tip sag. Damping is raised so the test settles quickly; it does not move the
// equilibrium.
double settled_sag(Scene s, int substeps, int iterations) {
  s.substeps = substeps;
  s.iterations = iterations;
  s.material.damping = 6;
  SceneSimulation sim;
  std::string err;
  EXPECT_TRUE(sim.init(s, &err)) << err;
  for (int f = 0; f < 150; ++f) {
    EXPECT_TRUE(sim.advance_frame(&err)) << err;
    if (f > 30 && sim.solver().kinetic_energy() < 1e-7) break;
  }
  return tip_sag(sim);
}

TEST(SimPhysics, BarSagsStaysAboveGroundAndComesToRest) {
  Scene s = small_bar();
  s.ground_height = -0.09;  // the settled tip would sag below this: the ground must hold it
  SceneSimulation sim;
  std::string err;
  ASSERT_TRUE(sim.init(s, &err)) << err;
  double peak = 0, lowest = 1e30;
  std::vector<double> energy;
  for (int f = 0; f < 120; ++f) {
    ASSERT_TRUE(sim.advance_frame(&err)) << err;
    for (const auto& x : sim.solver().positions()) {
      ASSERT_TRUE(x.allFinite());
      lowest = std::min(lowest, x.y());
    }
    energy.push_back(sim.solver().kinetic_energy());
    peak = std::max(peak, energy.back());
  }
  std::printf("bar: tip sag %.4f m, lowest %.5f m, peak KE %.3g J, final KE %.3g J\n", tip_sag(sim), lowest, peak,
              energy.back());
  EXPECT_GT(tip_sag(sim), 0.02);
  EXPECT_GE(lowest, s.ground_height - 1e-9);
  EXPECT_GT(peak, 0);
  EXPECT_LT(energy.back(), 1e-3 * peak);
  EXPECT_LT(*std::max_element(energy.end() - 30, energy.end()), *std::max_element(energy.begin(), energy.begin() + 30));
}

TEST(SimPhysics, SettledSagIndependentOfSubstepsAndIterations) {
  for (const Scene& s : {small_bar(), small_rope()}) {
    const double base = settled_sag(s, 20, 5);
    const double more_substeps = settled_sag(s, 40, 5);
    const double more_iterations = settled_sag(s, 20, 20);
    std::printf("%s: settled sag %.5f m (20 substeps, 5 it), %.5f (40, 5), %.5f (20, 20)\n", s.name.c_str(), base,
                more_substeps, more_iterations);
    EXPECT_GT(base, 0.01);
    EXPECT_LT(std::abs(more_substeps - base), 0.05 * base);
    EXPECT_LT(std::abs(more_iterations - base), 0.10 * base);
  }
}

}  // namespace
}  // namespace dcurve
