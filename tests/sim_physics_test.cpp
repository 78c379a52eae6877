// Physical behaviour of the XPBD simulator on small versions of the built-in scenes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>

#include "corpus/sim/scene.h"
#include "corpus/sim/simulation.h"

namespace dcurve {
namespace {

Scene builtin(const std::string& name) {
  Scene s;
  std::string err;
  EXPECT_TRUE(builtin_scene(name, &s, &err)) << err;
  return s;
}

// The two heavier tests take seconds in a plain optimized build but one to several minutes
// under a sanitizer or without optimization, which would blow the suite's time budget. They
// run no code the lighter tests here do not, so there they skip, saying so.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)  // clang's spelling of __SANITIZE_ADDRESS__
#define DCURVE_SIM_TEST_SANITIZED
#endif
#endif
#if defined(__OPTIMIZE__) && !defined(__SANITIZE_ADDRESS__) && !defined(DCURVE_SIM_TEST_SANITIZED)
constexpr bool kOptimized = true;
#else
constexpr bool kOptimized = false;
#endif

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

// Runs until the kinetic energy has fallen below 1e-6 J (at most 150 frames) and returns
// the tip sag. Damping is raised so the test settles quickly; it does not move the
// equilibrium.
double settled_sag(Scene s, int substeps, int iterations) {
  s.substeps = substeps;
  s.iterations = iterations;
  s.material.damping = 15;
  SceneSimulation sim;
  std::string err;
  EXPECT_TRUE(sim.init(s, &err)) << err;
  for (int f = 0; f < 150; ++f) {
    EXPECT_TRUE(sim.advance_frame(&err)) << err;
    if (f > 20 && sim.solver().kinetic_energy() < 1e-6) break;
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
  if (!kOptimized) GTEST_SKIP() << "about 1000 simulated frames: run it in an optimized, unsanitized build";
  for (const Scene& s : {small_bar(), small_rope()}) {
    const int n = s.substeps;
    const double base = settled_sag(s, n, 5);
    const double more_substeps = settled_sag(s, 2 * n, 5);
    const double more_iterations = settled_sag(s, n, 20);
    std::printf("%s: settled sag %.5f m (%d substeps, 5 it), %.5f (%d, 5), %.5f (%d, 20)\n", s.name.c_str(), base, n,
                more_substeps, 2 * n, more_iterations, n);
    EXPECT_GT(base, 0.01);
    EXPECT_LT(std::abs(more_substeps - base), 0.05 * base);
    EXPECT_LT(std::abs(more_iterations - base), 0.10 * base);
  }
}

// Volume enclosed by a closed surface (divergence theorem), m^3.
double enclosed_volume(const std::vector<float>& x, const std::vector<uint32_t>& faces) {
  double v = 0;
  for (size_t i = 0; i < faces.size(); i += 3) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = Eigen::Vector3d(x[3 * faces[i + k]], x[3 * faces[i + k] + 1], x[3 * faces[i + k] + 2]);
    v += p[0].dot(p[1].cross(p[2])) / 6;
  }
  return v;
}

TEST(SimPhysics, SoftBlobKeepsItsVolumeThroughTheImpact) {
  if (!kOptimized) GTEST_SKIP() << "1400 tets for 40 frames: run it in an optimized, unsanitized build";
  Scene s = builtin("blob");
  s.generator["divisions"] = 6;
  s.material.volume_compliance = 1e-7;  // bulk modulus 10 MPa against a 50 kPa Young's modulus
  s.frames = 40;
  Animation anim;
  std::string err;
  ASSERT_TRUE(simulate_scene(s, &anim, {}, &err)) << err;
  const double rest = enclosed_volume(anim.frames[0], anim.faces);
  double worst = 0, lowest = 1e30;
  for (const auto& frame : anim.frames) {
    worst = std::max(worst, std::abs(enclosed_volume(frame, anim.faces) / rest - 1));
    for (size_t i = 1; i < frame.size(); i += 3) lowest = std::min(lowest, double(frame[i]));
  }
  std::printf("blob: worst volume change %.3f%%, lowest point %.5f m\n", 100 * worst, lowest);
  EXPECT_GT(rest, 0);
  EXPECT_LT(lowest, 0.01);  // it did reach the ground ...
  EXPECT_GE(lowest, -1e-6);  // ... and never went through it
  EXPECT_LT(worst, 0.01);
}

TEST(SimPhysics, SameSceneGivesSameBytes) {
  Scene s = builtin("neck");
  s.generator["around"] = 12;
  s.generator["along"] = 8;
  s.frames = 6;
  Animation a, b;
  std::string err;
  ASSERT_TRUE(simulate_scene(s, &a, {}, &err)) << err;
  ASSERT_TRUE(simulate_scene(s, &b, {}, &err)) << err;
  ASSERT_EQ(a.frames.size(), 6u);
  ASSERT_EQ(a.faces, b.faces);
  for (size_t f = 0; f < a.frames.size(); ++f) {
    ASSERT_EQ(a.frames[f].size(), b.frames[f].size());
    EXPECT_EQ(0, std::memcmp(a.frames[f].data(), b.frames[f].data(), a.frames[f].size() * sizeof(float))) << f;
  }
  EXPECT_NE(0, std::memcmp(a.frames[0].data(), a.frames[5].data(), a.frames[0].size() * sizeof(float)));
}

TEST(SimPhysics, HandleTwistsAndLiftsTheNeckTop) {
  Scene s = builtin("neck");
  s.generator["around"] = 12;
  s.generator["along"] = 8;
  s.fps = 10;  // 10 frames = 1 s of the 2 s handle motion
  s.frames = 11;
  SceneSimulation sim;
  std::string err;
  ASSERT_TRUE(sim.init(s, &err)) << err;
  for (int f = 0; f < 10; ++f) ASSERT_TRUE(sim.advance_frame(&err)) << err;
  const auto& x = sim.solver().positions();
  const auto& rest = sim.solver().rest_positions();
  // After 1 s the top ring has turned pi/2 about +y around its centre and moved by (0.05, 0.05, 0).
  const Eigen::AngleAxisd turn(std::acos(-1.0) / 2, Eigen::Vector3d::UnitY());
  int top = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (rest[i].y() < 0.4 - 1e-6) continue;
    const Eigen::Vector3d centre(0, 0.4, 0);
    const Eigen::Vector3d expect = centre + turn * (rest[i] - centre) + Eigen::Vector3d(0.05, 0.05, 0);
    EXPECT_LT((x[i] - expect).norm(), 1e-9);
    ++top;
  }
  EXPECT_GT(top, 0);
  for (size_t i = 0; i < x.size(); ++i) {
    if (rest[i].y() <= 0) {
      EXPECT_EQ(x[i], rest[i]);  // the base is pinned
    }
  }
}

}  // namespace
}  // namespace dcurve
