// Curve extraction on procedural meshes: the partition invariant, the shape of the curves on
// meshes whose ideal curves are known (grid rows, tube lines/rings), u rules, split_curve,
// error handling, and that check_partition catches each kind of broken partition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "encoder/curves/extract.h"
#include "encoder/curves/report.h"

namespace dcurve {
namespace {

struct TestMesh {
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  uint32_t vertex_count() const { return uint32_t(xyz.size() / 3); }
  uint32_t add(double x, double y, double z) {
    xyz.insert(xyz.end(), {float(x), float(y), float(z)});
    return vertex_count() - 1;
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) { faces.insert(faces.end(), {a, b, c}); }
  // Two triangles per quad a-b-c-d (counter-clockwise).
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    tri(a, b, c);
    tri(a, c, d);
  }
};

// nx * ny vertices in the z = 0 plane, spacing 1 along x and `dy` along y.
TestMesh grid(uint32_t nx, uint32_t ny, double dy = 1.0) {
  TestMesh m;
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i) m.add(i, j * dy, 0.0);
  for (uint32_t j = 0; j + 1 < ny; ++j)
    for (uint32_t i = 0; i + 1 < nx; ++i) m.quad(j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i);
  return m;
}

// Open cylinder along x: `rings` rings of `around` vertices, radius r, ring spacing 1.
// With `caps`, one pole vertex closes each end (a closed genus-0 surface).
TestMesh tube(uint32_t around, uint32_t rings, double r, bool caps) {
  TestMesh m;
  for (uint32_t j = 0; j < rings; ++j)
    for (uint32_t i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around;
      m.add(j, r * std::cos(a), r * std::sin(a));
    }
  for (uint32_t j = 0; j + 1 < rings; ++j)
    for (uint32_t i = 0; i < around; ++i) {
      const uint32_t i1 = (i + 1) % around;
      m.quad(j * around + i, (j + 1) * around + i, (j + 1) * around + i1, j * around + i1);
    }
  if (caps) {
    const uint32_t s = m.add(-1.0, 0, 0), e = m.add(rings, 0, 0);
    for (uint32_t i = 0; i < around; ++i) {
      const uint32_t i1 = (i + 1) % around;
      m.tri(s, i, i1);
      m.tri(e, (rings - 1) * around + i1, (rings - 1) * around + i);
    }
  }
  return m;
}

// Appends b's vertices and faces to a (a new connected component).
void append(TestMesh* a, const TestMesh& b, double shift) {
  const uint32_t base = a->vertex_count();
  for (size_t k = 0; k < b.xyz.size(); k += 3) a->add(b.xyz[k] + shift, b.xyz[k + 1], b.xyz[k + 2]);
  for (uint32_t f : b.faces) a->faces.push_back(base + f);
}

Curves extract_ok(const TestMesh& m, CurveOptions options = {}) {
  Curves curves;
  std::string error;
  EXPECT_TRUE(extract_curves(m.xyz, m.vertex_count(), m.faces, options, &curves, &error)) << error;
  EXPECT_TRUE(check_partition(curves, m.vertex_count(), m.faces, &error)) << error;
  return curves;
}

uint32_t size_of(const Curves& c, uint32_t k) { return c.offsets[k + 1] - c.offsets[k]; }

// u starts at 0, ends at 1 on open curves with >= 2 points, strictly below 1 at the end of a
// closed one, and never decreases.
void expect_u_endpoints(const Curves& c) {
  for (uint32_t k = 0; k < c.curve_count(); ++k) {
    const uint32_t b = c.offsets[k], n = size_of(c, k);
    EXPECT_EQ(c.u[b], 0.f) << "curve " << k;
    if (n >= 2 && !c.closed[k]) {
      EXPECT_EQ(c.u[b + n - 1], 1.f) << "curve " << k;
    }
    if (c.closed[k]) {
      EXPECT_LT(c.u[b + n - 1], 1.f) << "curve " << k;
    }
  }
}

TEST(Curves, GridGivesStraightFullRows) {
  const TestMesh m = grid(40, 30);
  CurveOptions opt;
  opt.target_points = 1000;
  opt.bend_weight = 1.0;  // a hairpin joining two rows costs more than a second curve
  const Curves c = extract_ok(m, opt);
  const CurveReport r = curve_report(c, m.xyz);
  // The ideal is 30 rows of 40 (or 40 columns of 30); a random walk would turn often.
  EXPECT_LE(r.curves, 40u);
  EXPECT_LT(r.mean_turning_angle_deg, 1.0);
  EXPECT_EQ(r.short_curve_vertex_fraction, 0.0);
  expect_u_endpoints(c);
}

TEST(Curves, BendWeightTradesCurveCountForTurns) {
  const TestMesh m = grid(20, 15);
  CurveOptions opt;
  opt.target_points = 1000;
  std::vector<CurveReport> reports;
  for (double w : {1.0, 0.3, 0.0}) {
    opt.bend_weight = w;
    reports.push_back(curve_report(extract_ok(m, opt), m.xyz));
  }
  // Cheaper bends: rows get joined at the border into longer, more bent curves.
  EXPECT_GT(reports[0].curves, reports[2].curves);
  EXPECT_LT(reports[0].mean_turning_angle_deg, reports[2].mean_turning_angle_deg);
  EXPECT_GE(reports[0].curves, reports[1].curves);
  EXPECT_GE(reports[1].curves, reports[2].curves);
}

TEST(Curves, TargetLengthBoundsEveryCurve) {
  const TestMesh m = grid(50, 50);
  for (uint32_t target : {2u, 7u, 25u, 64u}) {
    CurveOptions opt;
    opt.target_points = target;
    const Curves c = extract_ok(m, opt);
    uint32_t longest = 0;
    for (uint32_t k = 0; k < c.curve_count(); ++k) longest = std::max(longest, size_of(c, k));
    EXPECT_LE(longest, target);
    // Cut evenly: a 50-point row with target 7 becomes 8 pieces of 6-7, not 7 + 1.
    if (target >= 7) {
      EXPECT_GT(curve_report(c, m.xyz).median_points_per_curve, target / 2.0);
    }
  }
}

TEST(Curves, TubeCurvesAreLongAndStraightOrRings) {
  const TestMesh m = tube(24, 40, 3.0, false);
  CurveOptions opt;
  opt.target_points = 1000;
  const Curves c = extract_ok(m, opt);
  const CurveReport r = curve_report(c, m.xyz);
  // Either 24 lines of 40 or 40 closed rings of 24 (turn 15 degrees each); both are smooth.
  EXPECT_LE(r.curves, 48u);
  EXPECT_LE(r.mean_turning_angle_deg, 16.0);
  uint32_t closed = 0;
  for (uint8_t f : c.closed) closed += f;
  for (uint32_t k = 0; k < c.curve_count(); ++k)
    if (c.closed[k]) {
      EXPECT_GE(size_of(c, k), 3u);
    }
  expect_u_endpoints(c);
  std::printf("tube: %u curves, %u closed, mean turn %.1f deg\n", r.curves, closed, r.mean_turning_angle_deg);
}

TEST(Curves, ClosedCapsuleHasFewShortCurves) {
  const TestMesh m = tube(20, 30, 2.0, true);
  const Curves c = extract_ok(m);
  const CurveReport r = curve_report(c, m.xyz);
  EXPECT_LT(r.short_curve_vertex_fraction, 0.02);
  EXPECT_GT(r.mean_points_per_curve, 15.0);
  expect_u_endpoints(c);
}

TEST(Curves, ComponentsBoundariesAndIsolatedVertices) {
  TestMesh m = grid(12, 9);
  append(&m, tube(10, 8, 1.0, true), 100.0);
  append(&m, grid(2, 2), 200.0);  // a single quad
  const uint32_t lonely = m.add(-50, -50, -50);
  m.add(-60, -50, -50);  // a second isolated vertex
  const Curves c = extract_ok(m);
  expect_u_endpoints(c);
  uint32_t singles = 0;
  for (uint32_t k = 0; k < c.curve_count(); ++k)
    if (size_of(c, k) == 1) {
      ++singles;
      EXPECT_GE(c.vertices[c.offsets[k]], lonely);  // only the isolated vertices are alone
      EXPECT_FALSE(c.closed[k]);
    }
  EXPECT_EQ(singles, 2u);
  // No curve crosses components: the shift of 100 between them exceeds any edge.
  for (uint32_t k = 0; k < c.curve_count(); ++k)
    for (uint32_t i = c.offsets[k] + 1; i < c.offsets[k + 1]; ++i)
      EXPECT_LT(std::fabs(m.xyz[3 * c.vertices[i]] - m.xyz[3 * c.vertices[i - 1]]), 50.f);
}

TEST(Curves, OnlyIsolatedVertices) {
  TestMesh m;
  m.add(0, 0, 0);
  m.add(1, 0, 0);
  const Curves c = extract_ok(m);
  EXPECT_EQ(c.curve_count(), 2u);
  EXPECT_EQ(c.u, std::vector<float>({0.f, 0.f}));
}

TEST(Curves, Deterministic) {
  TestMesh m = tube(16, 20, 1.5, true);
  append(&m, grid(20, 10), 50.0);
  const Curves a = extract_ok(m), b = extract_ok(m);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_EQ(a.offsets, b.offsets);
  EXPECT_EQ(a.closed, b.closed);
  EXPECT_EQ(a.u, b.u);
}

TEST(Curves, ChordLengthAndCoordinateRangeRules) {
  // A 1 x 6 strip with uneven spacing along x: rows are the obvious curves.
  TestMesh m;
  const double xs[6] = {0, 1, 3, 4, 8, 10};
  for (int j = 0; j < 2; ++j)
    for (double x : xs) m.add(x, 0.3 * j, 0);
  for (uint32_t i = 0; i + 1 < 6; ++i) m.quad(i, i + 1, 6 + i + 1, 6 + i);
  for (ParamRule rule : {ParamRule::ChordLength, ParamRule::CoordinateRange}) {
    CurveOptions opt;
    opt.u_rule = rule;
    opt.bend_weight = 1.0;  // keep the two rows apart rather than joined by a hairpin
    const Curves c = extract_ok(m, opt);
    ASSERT_EQ(c.curve_count(), 2u);
    for (uint32_t k = 0; k < 2; ++k) {
      ASSERT_EQ(size_of(c, k), 6u);
      const uint32_t* v = &c.vertices[c.offsets[k]];
      const double x0 = m.xyz[3 * v[0]], x5 = m.xyz[3 * v[5]];
      // Along a straight monotone row both rules reduce to eq. (10): (x - x_first) / range.
      for (uint32_t i = 0; i < 6; ++i)
        EXPECT_NEAR(c.u[c.offsets[k] + i], (m.xyz[3 * v[i]] - x0) / (x5 - x0), 1e-6);
    }
  }
  // On a bent path they differ: chord length counts the y step, the x range rule does not.
  TestMesh bent;
  bent.add(0, 0, 0);
  bent.add(1, 0, 0);
  bent.add(1, 1, 0);
  bent.add(3, 1, 0);
  Curves c;
  c.vertices = {0, 1, 2, 3};
  c.offsets = {0, 4};
  c.closed = {0};
  c.u.assign(4, 0.f);
  parameterize_curve(&c, 0, bent.xyz, ParamRule::ChordLength);
  EXPECT_NEAR(c.u[2], 0.5, 1e-6);
  parameterize_curve(&c, 0, bent.xyz, ParamRule::CoordinateRange);
  EXPECT_NEAR(c.u[1], 1.0 / 3.0, 1e-6);
  EXPECT_NEAR(c.u[2], 1.0 / 3.0, 1e-6);
}

TEST(Curves, ClosedCurveUCountsTheClosingStep) {
  // A square ring of four unit steps: u = 0, 1/4, 1/2, 3/4.
  TestMesh m;
  m.add(0, 0, 0);
  m.add(1, 0, 0);
  m.add(1, 1, 0);
  m.add(0, 1, 0);
  Curves c;
  c.vertices = {0, 1, 2, 3};
  c.offsets = {0, 4};
  c.closed = {1};
  c.u.assign(4, 0.f);
  parameterize_curve(&c, 0, m.xyz, ParamRule::ChordLength);
  EXPECT_EQ(c.u, std::vector<float>({0.f, 0.25f, 0.5f, 0.75f}));
}

TEST(Curves, SplitOpenAndClosedCurves) {
  const TestMesh m = tube(12, 6, 1.0, false);
  CurveOptions opt;
  opt.target_points = 1000;
  Curves c = extract_ok(m, opt);
  std::string error;
  // Split every curve in the middle, then split a closed one if there is any.
  const uint32_t before = c.curve_count();
  const std::vector<uint32_t> vertices_before = c.vertices;
  uint32_t closed_index = UINT32_MAX;
  for (uint32_t k = 0; k < c.curve_count(); ++k)
    if (c.closed[k]) closed_index = k;
  if (closed_index != UINT32_MAX) {
    const uint32_t n = size_of(c, closed_index), b = c.offsets[closed_index];
    const std::vector<uint32_t> ring(c.vertices.begin() + b, c.vertices.begin() + b + n);
    split_curve(&c, closed_index, 3, m.xyz, ParamRule::ChordLength);
    EXPECT_EQ(c.curve_count(), before);
    EXPECT_FALSE(c.closed[closed_index]);
    EXPECT_EQ(c.vertices[b], ring[3]);
    EXPECT_EQ(c.vertices[b + n - 1], ring[2]);
    EXPECT_EQ(c.u[b + n - 1], 1.f);
  }
  const uint32_t open_index = c.closed[0] ? 1 : 0;
  const uint32_t n = size_of(c, open_index);
  ASSERT_GE(n, 2u);
  const uint32_t curves_before_split = c.curve_count();
  split_curve(&c, open_index, n / 2, m.xyz, ParamRule::CoordinateRange);
  EXPECT_EQ(c.curve_count(), curves_before_split + 1);
  EXPECT_EQ(size_of(c, open_index), n / 2);
  EXPECT_EQ(size_of(c, open_index + 1), n - n / 2);
  EXPECT_TRUE(check_partition(c, m.vertex_count(), m.faces, &error)) << error;
  expect_u_endpoints(c);
  EXPECT_THROW(split_curve(&c, open_index, 0, m.xyz, ParamRule::ChordLength), std::invalid_argument);
  EXPECT_THROW(split_curve(&c, c.curve_count(), 1, m.xyz, ParamRule::ChordLength), std::invalid_argument);
}

TEST(Curves, ClearErrors) {
  Curves c;
  std::string error;
  CurveOptions opt;
  // Three triangles on one edge.
  TestMesh fan;
  for (int k = 0; k < 5; ++k) fan.add(k, k * k, 0.1 * k);
  fan.tri(0, 1, 2);
  fan.tri(1, 0, 3);
  fan.tri(0, 1, 4);
  EXPECT_FALSE(extract_curves(fan.xyz, 5, fan.faces, opt, &c, &error));
  EXPECT_NE(error.find("non-manifold"), std::string::npos) << error;
  EXPECT_NE(error.find("face 2"), std::string::npos) << error;

  TestMesh g = grid(3, 3);
  std::vector<uint32_t> bad = g.faces;
  bad[4] = 99;
  EXPECT_FALSE(extract_curves(g.xyz, g.vertex_count(), bad, opt, &c, &error));
  EXPECT_NE(error.find("vertex >= vertex count"), std::string::npos) << error;
  bad = g.faces;
  bad[1] = bad[0];
  EXPECT_FALSE(extract_curves(g.xyz, g.vertex_count(), bad, opt, &c, &error));
  EXPECT_NE(error.find("repeats a vertex"), std::string::npos) << error;
  EXPECT_FALSE(extract_curves(g.xyz, g.vertex_count() + 1, g.faces, opt, &c, &error));
  std::vector<float> nan_xyz = g.xyz;
  nan_xyz[5] = NAN;
  EXPECT_FALSE(extract_curves(nan_xyz, g.vertex_count(), g.faces, opt, &c, &error));
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
  opt.target_points = 1;
  EXPECT_FALSE(extract_curves(g.xyz, g.vertex_count(), g.faces, opt, &c, &error));
  EXPECT_NE(error.find("target_points"), std::string::npos) << error;
  opt.target_points = 8;
  opt.bend_weight = -1.0;
  EXPECT_FALSE(extract_curves(g.xyz, g.vertex_count(), g.faces, opt, &c, &error));
  EXPECT_NE(error.find("bend_weight"), std::string::npos) << error;
  EXPECT_TRUE(c.vertices.empty());  // *out untouched on failure
}

TEST(Curves, BowTieAndFlippedNeighbours) {
  // Two triangles sharing only vertex 0: OpenMesh accepts this non-manifold vertex, and the
  // curves must still partition the five vertices.
  TestMesh bow;
  bow.add(0, 0, 0);
  bow.add(1, 1, 0);
  bow.add(1, -1, 0);
  bow.add(-1, 1, 0);
  bow.add(-1, -1, 0);
  bow.tri(0, 2, 1);
  bow.tri(0, 3, 4);
  extract_ok(bow);

  // Two triangles on one edge with opposite orientation: refused with a message naming it.
  // grid(2, 2) is (0, 1, 3) + (0, 3, 2); flipping the second makes both run 3 -> 0.
  TestMesh flipped = grid(2, 2);
  ASSERT_EQ(flipped.faces, std::vector<uint32_t>({0, 1, 3, 0, 3, 2}));
  flipped.faces = {0, 1, 3, 0, 2, 3};
  Curves c;
  std::string error;
  EXPECT_FALSE(extract_curves(flipped.xyz, flipped.vertex_count(), flipped.faces, CurveOptions{}, &c, &error));
  EXPECT_NE(error.find("face 1"), std::string::npos) << error;
}

TEST(Curves, CheckPartitionCatchesEachBreak) {
  const TestMesh m = grid(4, 3);
  const Curves good = extract_ok(m);
  std::string error;
  ASSERT_TRUE(check_partition(good, m.vertex_count(), m.faces, &error));

  Curves bad = good;
  bad.vertices[1] = bad.vertices[0];
  EXPECT_FALSE(check_partition(bad, m.vertex_count(), m.faces, &error));
  EXPECT_NE(error.find("more than one"), std::string::npos) << error;

  // Two far corners of the grid are never adjacent.
  bad = Curves{};
  bad.vertices.resize(12);
  std::iota(bad.vertices.begin(), bad.vertices.end(), 0u);
  std::swap(bad.vertices[1], bad.vertices[11]);
  bad.offsets = {0, 12};
  bad.closed = {0};
  bad.u.assign(12, 0.f);
  EXPECT_FALSE(check_partition(bad, m.vertex_count(), m.faces, &error));
  EXPECT_NE(error.find("share no mesh edge"), std::string::npos) << error;

  bad = good;
  uint32_t longest = 0;
  for (uint32_t k = 0; k < bad.curve_count(); ++k)
    if (size_of(bad, k) > size_of(bad, longest)) longest = k;
  ASSERT_GE(size_of(bad, longest), 3u);
  bad.closed[longest] = 1;  // a straight row's ends are not adjacent
  EXPECT_FALSE(check_partition(bad, m.vertex_count(), m.faces, &error));
  EXPECT_NE(error.find("closed"), std::string::npos) << error;

  bad = good;
  bad.u[bad.offsets[longest] + 1] = 1.f;
  bad.u[bad.offsets[longest] + 2] = 0.5f;
  EXPECT_FALSE(check_partition(bad, m.vertex_count(), m.faces, &error));
  EXPECT_NE(error.find("decreases"), std::string::npos) << error;

  bad = good;
  bad.u[0] = 1.5f;
  EXPECT_FALSE(check_partition(bad, m.vertex_count(), m.faces, &error));

  bad = good;
  bad.vertices.pop_back();
  EXPECT_FALSE(check_partition(bad, m.vertex_count(), m.faces, &error));
}

}  // namespace
}  // namespace dcurve
