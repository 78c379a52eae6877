// The spatial modes whose weights come from a geometry frame (codec/common/predictors.h,
// format_spec/residual.md): Geometric locates a vertex against its parallelogram's
// triangle, Fit fits an affine function to up to 16 decoded vertices; both predict an affine
// motion of an irregular mesh where Parallelogram cannot, and a payload naming an unusable
// geometry frame is rejected.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "codec/common/predictors.h"
#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "codec/compress/residual_values.h"
#include "codec/decompress/residual_decoder.h"
#include "container_bytes.h"

namespace dcurve {
namespace {

// A traversal of four vertices where vertex 3 has the one parallelogram (0, 1, 2).
Traversal one_triangle() {
  Traversal t;
  t.order = {0, 1, 2, 3};
  t.nb_offsets = {0, 0, 0, 0, 0};
  t.para_offsets = {0, 0, 0, 0, 1};
  t.para = {0, 1, 2};
  return t;
}

TEST(GeometricWeights, LocateTheVertexAgainstItsTriangle) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-1.0, 1.0), weight(-2.0, 2.0);
  const Traversal t = one_triangle();
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Scales from a few grid steps to beyond the 12 bits the weights are computed in.
    const double scale = std::ldexp(1.0, 4 + trial % 26);
    double p[3][3];
    for (auto& row : p)
      for (double& x : row) x = coord(rng) * scale;
    const double alpha = weight(rng), beta = weight(rng);  // where v lies, before rounding
    int32_t g[12];
    for (int k = 0; k < 3; ++k) {
      for (int u = 0; u < 3; ++u) g[u * 3 + k] = int32_t(std::lround(p[u][k]));
      g[9 + k] = int32_t(std::lround(p[0][k] + alpha * (p[1][k] - p[0][k]) + beta * (p[2][k] - p[0][k])));
    }
    // The least-squares (alpha, beta) of the rounded coordinates, in binary64.
    double d1[3], d2[3], x[3];
    for (int k = 0; k < 3; ++k) {
      d1[k] = double(g[3 + k]) - g[k];
      d2[k] = double(g[6 + k]) - g[k];
      x[k] = double(g[9 + k]) - g[k];
    }
    auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
    const double g11 = dot(d1, d1), g12 = dot(d1, d2), g22 = dot(d2, d2), det = g11 * g22 - g12 * g12;
    // Only well-shaped triangles (sin of the angle at a above 0.45, no edge under a
    // quarter of the longest distance), as parallelograms of a mesh are: on thin or small
    // ones the 12-bit cut below moves the solution more than the bound.
    const double longest = std::max({g11, g22, dot(x, x)});
    if (det < 0.2 * g11 * g22 || std::min(g11, g22) < longest / 16) continue;
    const double a_ls = (g22 * dot(d1, x) - g12 * dot(d2, x)) / det;
    const double b_ls = (g11 * dot(d2, x) - g12 * dot(d1, x)) / det;
    const std::vector<int32_t> w = geometric_weights(t, g);
    ASSERT_EQ(w.size(), 2u);
    // The weights are computed from the coordinates cut to 12 bits (an error of one unit
    // in 4096 of the largest; the triangle's shape can amplify it a few times), then
    // rounded to 1/256 and clamped to [-4, 4].
    if (std::fabs(a_ls) > 3.9 || std::fabs(b_ls) > 3.9) continue;
    const double allowed = 0.5 + 256 * 12 * (std::fabs(a_ls) + std::fabs(b_ls) + 1) / 4096;
    EXPECT_NEAR(w[0], 256 * a_ls, allowed) << "trial " << trial;
    EXPECT_NEAR(w[1], 256 * b_ls, allowed) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 200);
  // A degenerate triangle falls back to the plain parallelogram.
  const int32_t line[12] = {0, 0, 0, 10, 0, 0, 20, 0, 0, 5, 5, 0};
  EXPECT_EQ(geometric_weights(t, line), (std::vector<int32_t>{256, -256}));
  // Extreme coordinates stay in range (no overflow) and keep the weights clamped.
  const int32_t far[12] = {INT32_MIN, INT32_MIN, 0, INT32_MAX, INT32_MIN, 0, INT32_MIN, INT32_MIN + 1, 0,
                           INT32_MAX, INT32_MAX, 0};
  for (int32_t x : geometric_weights(t, far)) {
    EXPECT_GE(x, -kGeometricLimit);
    EXPECT_LE(x, kGeometricLimit);
  }
}

// A flat, irregular mesh (a jittered grid) and the same mesh moved by an affine map: the
// displacement field is affine, so Geometric predicts it to rounding, Parallelogram only
// where the mesh happens to be a parallelogram.
struct AffineCase {
  Model model;
  std::vector<int32_t> q;  // 2 frames
};

AffineCase affine_case() {
  constexpr uint32_t side = 12;
  AffineCase c;
  Model& m = c.model;
  m.meta = {side * side, 2, 30.0, 1e-3, 1.0, ""};
  for (uint32_t i = 0; i + 1 < side; ++i)
    for (uint32_t j = 0; j + 1 < side; ++j) {
      const uint32_t a = i * side + j, b = a + 1, d = a + side, e = d + 1;
      m.faces.insert(m.faces.end(), {a, b, e, a, e, d});
    }
  m.residual.step = 1e-3;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> jitter(-35, 35);
  std::vector<int32_t> f0;
  for (uint32_t i = 0; i < side; ++i)
    for (uint32_t j = 0; j < side; ++j) f0.insert(f0.end(), {int32_t(100 * j) + jitter(rng), int32_t(100 * i) + jitter(rng), 0});
  const double ang = 0.3, s = 1.2;
  c.q = f0;
  for (size_t v = 0; v < f0.size(); v += 3) {
    const double x = f0[v], y = f0[v + 1];
    c.q.push_back(int32_t(std::lround(s * (std::cos(ang) * x - std::sin(ang) * y) + 57)));
    c.q.push_back(int32_t(std::lround(s * (std::sin(ang) * x + std::cos(ang) * y) - 31)));
    c.q.push_back(int32_t(std::lround(0.25 * x - 0.5 * y)));
  }
  return c;
}

// Frame 0 from its own neighbours, frame 1 from frame 0 with `spatial` (geometry: frame 0).
PredictorPlan two_frame_plan(SpatialMode spatial) {
  const PredictorChoice intra{PredictorKind::None, 0, 0, SpatialMode::Parallelogram, 0};
  const PredictorChoice inter{PredictorKind::Reference, 0, 0, spatial, 0};
  return uniform_plan({0, 1}, {intra, intra, intra, inter, inter, inter});
}

// Codes c.q with `plan` into c.model's payload and checks it decodes to c.q again.
void expect_round_trip(AffineCase* c, const PredictorPlan& plan) {
  c->model.residual.payload = encode_residuals(c->model, c->q, &plan);
  ASSERT_FALSE(c->model.residual.payload.empty());
  std::vector<int32_t> back;
  std::string err;
  ASSERT_TRUE(decode_residuals(c->model, &back, &err)) << err;
  EXPECT_EQ(back, c->q);
}

// Residuals of frame 1 predicted from frame 0 with the given spatial mode.
std::vector<int64_t> frame1_residuals(const AffineCase& c, SpatialMode spatial) {
  const std::vector<int64_t> all = residual_values(c.model, c.q, two_frame_plan(spatial));
  EXPECT_EQ(all.size(), c.q.size());
  return std::vector<int64_t>(all.begin() + std::ptrdiff_t(all.size() / 2), all.end());
}

TEST(GeometricPrediction, AffineMotionOfAnIrregularMeshToRounding) {
  const AffineCase c = affine_case();
  int64_t geo_sum = 0, para_sum = 0, geo_max = 0, with_para = 0;
  const std::vector<int64_t> geo = frame1_residuals(c, SpatialMode::Geometric);
  const std::vector<int64_t> para = frame1_residuals(c, SpatialMode::Parallelogram);
  ASSERT_EQ(geo.size(), para.size());
  // Residuals come in traversal order; positions without a parallelogram fall back to
  // Mean in both modes.
  const Traversal t = build_traversal(c.model);
  for (size_t i = 0; i < geo.size(); ++i) {
    const size_t pos = i / 3;
    if (t.para_offsets[pos] == t.para_offsets[pos + 1]) continue;
    geo_sum += std::llabs(geo[i]);
    para_sum += std::llabs(para[i]);
    geo_max = std::max<int64_t>(geo_max, std::llabs(geo[i]));
    ++with_para;
  }
  EXPECT_LE(geo_max, 3);
  EXPECT_LT(geo_sum * 4, para_sum) << "geometric " << geo_sum << ", parallelogram " << para_sum;
  EXPECT_GT(with_para, int64_t(geo.size() / 2));
}

TEST(GeometricPrediction, RoundTripsAndRejectsAnUnusableGeometryFrame) {
  AffineCase c = affine_case();
  const PredictorPlan plan = two_frame_plan(SpatialMode::Geometric);
  expect_round_trip(&c, plan);
  if (HasFatalFailure()) return;
  std::vector<int32_t> back;
  std::string err;
  // The encoder refuses a geometry frame that is the frame itself.
  PredictorPlan self = plan;
  for (PredictorChoice& p : self.frames[1].candidates[0]) p.g = 1;
  EXPECT_TRUE(encode_residuals(c.model, c.q, &self).empty());
  // Frame 1's predictor is byte 0x41 (Reference | Geometric << 4), r0 = zigzag(-1) = 1,
  // then g: point it at frame 1 itself (zigzag(0) = 0) or at frame 2, which does not exist.
  const bool faces = !c.model.faces.empty();
  const std::vector<uint8_t> frame0 = {0, 1, 0x20, 0x20, 0x20};
  for (uint8_t bad : {uint8_t(0x00), uint8_t(0x02)}) {
    c.model.residual.payload =
        testing::table_payload(2, faces, {{7, 1}, frame0, {0, 1, 0x41, 1, bad, 0x41, 1, 1, 0x41, 1, 1}});
    EXPECT_FALSE(decode_residuals(c.model, &back, &err));
    EXPECT_NE(err.find("unavailable frame"), std::string::npos) << err;
  }
  // Spatial mode 6 does not exist.
  c.model.residual.payload = testing::table_payload(2, faces, {{7, 1}, frame0, {0, 1, 0x61, 1, 0x21, 1, 0x21, 1}});
  EXPECT_FALSE(decode_residuals(c.model, &back, &err));
  EXPECT_NE(err.find("malformed"), std::string::npos) << err;
}

// Each geometry frame costs a decoder a table of weights: a frame may name at most
// kMaxGeometryFrames of them, which encoder and decoder both enforce.
TEST(GeometricPrediction, AFrameNamesAtMostEightGeometryFrames) {
  AffineCase c = affine_case();
  constexpr uint32_t F = 10;
  const std::vector<int32_t> two = c.q;
  for (uint32_t f = 2; f < F; f += 2) c.q.insert(c.q.end(), two.begin(), two.end());
  c.model.meta.frame_count = F;
  auto plan_naming = [&](uint32_t geometry_frames) {
    PredictorPlan plan = uniform_plan({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, std::vector<PredictorChoice>(3 * F));
    for (uint32_t f = 0; f + 1 < F; ++f)
      for (PredictorChoice& p : plan.frames[f].candidates[0]) p = {PredictorKind::None, 0, 0, SpatialMode::Mean, 0};
    FramePredictors& last = plan.frames[F - 1];
    last.candidates.assign(3, {});
    last.cluster_candidate.assign(cluster_count(c.model.meta.vertex_count, plan.cluster_size), 0);
    for (uint32_t j = 0; j < 3; ++j)
      for (uint32_t a = 0; a < 3; ++a)
        last.candidates[j][a] = {PredictorKind::Reference, F - 2, 0, SpatialMode::Geometric, (j * 3 + a) % geometry_frames};
    return plan;
  };
  PredictorPlan nine = plan_naming(9);
  EXPECT_TRUE(encode_residuals(c.model, c.q, &nine).empty());
  expect_round_trip(&c, plan_naming(8));
}

// Fit weights against the same least squares in binary64 on the same 7-bit offsets: the
// integer algorithm (adjugate, shifts, rounding to 1/65536) must agree to the rounding.
TEST(FitWeights, MatchTheRidgeLeastSquaresOfTheScaledOffsets) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const uint32_t n = 2 + uint32_t(trial % 15);  // 2..16 points
    const bool flat = trial % 3 == 0;             // a flat patch, as on a box face
    const double scale = std::ldexp(1.0, 3 + trial % 27);
    Traversal t;
    t.order.resize(n + 1);
    for (uint32_t i = 0; i <= n; ++i) t.order[i] = i;
    t.fit_offsets.assign(n + 2, 0);
    t.fit_offsets[n + 1] = n;
    for (uint32_t j = 0; j < n; ++j) t.fit.push_back(j);
    std::vector<int32_t> g(size_t(n + 1) * 3);
    for (size_t i = 0; i < g.size(); ++i) g[i] = (flat && i % 3 == 2) ? 7 : int32_t(std::lround(coord(rng) * scale));
    const std::vector<int32_t> w = fit_weights(t, g.data());
    ASSERT_EQ(w.size(), size_t(n));
    EXPECT_EQ(w[0], 0);
    // The reference: offsets to v cut to 7 bits as the format does, then binary64.
    int64_t m = 0;
    for (uint32_t j = 0; j < n; ++j)
      for (int k = 0; k < 3; ++k) m = std::max<int64_t>(m, std::llabs(int64_t(g[j * 3 + k]) - g[n * 3 + k]));
    int shift = 0;
    while ((m >> shift) > 127) ++shift;
    double d[16][3], s[3] = {0, 0, 0}, c[3][3] = {{16, 0, 0}, {0, 16, 0}, {0, 0, 16}};
    for (uint32_t j = 0; j < n; ++j)
      for (int k = 0; k < 3; ++k) d[j][k] = std::floor(std::ldexp(double(int64_t(g[j * 3 + k]) - g[n * 3 + k]), -shift));
    for (uint32_t j = 0; j < n; ++j)
      for (int k = 0; k < 3; ++k) {
        s[k] += d[j][k];
        for (int l = 0; l < 3; ++l) c[k][l] += d[j][k] * d[j][l];
      }
    // u = C^-1 s by Cramer's rule.
    auto det3 = [](const double a[3][3]) {
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double det = det3(c);
    double u[3];
    for (int k = 0; k < 3; ++k) {
      double ck[3][3];
      for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col) ck[r][col] = col == k ? s[r] : c[r][col];
      u[k] = det3(ck) / det;
    }
    const double den = n - (u[0] * s[0] + u[1] * s[1] + u[2] * s[2]);
    double weight_sum = 0;
    for (uint32_t j = 0; j < n; ++j) {
      const double wj = (1 - (u[0] * d[j][0] + u[1] * d[j][1] + u[2] * d[j][2])) / den;
      weight_sum += wj;
      if (j == 0 || std::fabs(wj) > 15) continue;  // beyond the clamp (16)
      EXPECT_NEAR(w[j], 65536 * wj, 0.5 + 65536 * 1e-7 * (1 + std::fabs(wj))) << "trial " << trial << " j " << j;
      ++checked;
    }
    EXPECT_NEAR(weight_sum, 1.0, 1e-9);  // affine: the weights of the exact fit sum to 1
  }
  EXPECT_GT(checked, 10000);
}

TEST(FitWeights, ExtremeCoordinatesStayWithinTheClamp) {
  Traversal t;
  t.order = {0, 1, 2, 3};
  t.fit_offsets = {0, 0, 0, 0, 3};
  t.fit = {0, 1, 2};
  const int32_t far[12] = {INT32_MIN, INT32_MIN, 0, INT32_MAX, INT32_MIN, 0, INT32_MIN, INT32_MIN + 1, 0,
                           INT32_MAX, INT32_MAX, INT32_MAX};
  for (int32_t x : fit_weights(t, far)) {
    EXPECT_GE(x, -kFitLimit);
    EXPECT_LE(x, kFitLimit);
  }
  // All points on v: every offset is 0, the fit is the mean of the values.
  const int32_t same[12] = {5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5, 5};
  const std::vector<int32_t> w = fit_weights(t, same);
  EXPECT_EQ(w, (std::vector<int32_t>{0, 21845, 21845}));
}

TEST(FitPrediction, AffineMotionOfAnIrregularMeshToRounding) {
  const AffineCase c = affine_case();
  const std::vector<int64_t> fit = frame1_residuals(c, SpatialMode::Fit);
  const std::vector<int64_t> para = frame1_residuals(c, SpatialMode::Parallelogram);
  int64_t fit_sum = 0, para_sum = 0, fit_max = 0;
  // From the fifth position on, every vertex has at least three decoded points around it.
  for (size_t i = 15; i < fit.size(); ++i) {
    fit_sum += std::llabs(fit[i]);
    para_sum += std::llabs(para[i]);
    fit_max = std::max<int64_t>(fit_max, std::llabs(fit[i]));
  }
  // Offsets are cut to 7 bits (Geometric: 12): on a 2-ring some 300 grid units wide, a
  // position moves by up to 4 units, the field by up to 1.2 times that.
  EXPECT_LE(fit_max, 6);
  EXPECT_LT(fit_sum * 4, para_sum) << "fit " << fit_sum << ", parallelogram " << para_sum;
}

TEST(FitPrediction, RoundTripsAndRejectsAnUnusableGeometryFrame) {
  AffineCase c = affine_case();
  expect_round_trip(&c, two_frame_plan(SpatialMode::Fit));
  if (HasFatalFailure()) return;
  // Frame 1's predictor is byte 0x51 (Reference | Fit << 4), r0 = 1, then g = 0: frame 1
  // itself.
  std::vector<int32_t> back;
  std::string err;
  c.model.residual.payload = testing::table_payload(
      2, !c.model.faces.empty(), {{7, 1}, {0, 1, 0x20, 0x20, 0x20}, {0, 1, 0x51, 1, 0, 0x51, 1, 1, 0x51, 1, 1}});
  EXPECT_FALSE(decode_residuals(c.model, &back, &err));
  EXPECT_NE(err.find("unavailable frame"), std::string::npos) << err;
}

// The Fit set: a vertex's earlier neighbours first, then earlier second-ring vertices, at
// most kMaxFitPoints, all decoded before it.
TEST(FitPrediction, FitSetsHoldDecodedNeighboursThenTheSecondRing) {
  const AffineCase c = affine_case();
  const Traversal t = build_traversal(c.model);
  std::vector<uint32_t> pos(t.order.size());
  for (uint32_t i = 0; i < t.order.size(); ++i) pos[t.order[i]] = i;
  size_t largest = 0;
  for (uint32_t i = 0; i < t.order.size(); ++i) {
    const uint32_t begin = t.fit_offsets[i], end = t.fit_offsets[i + 1];
    const uint32_t nb = t.nb_offsets[i + 1] - t.nb_offsets[i];
    ASSERT_LE(end - begin, kMaxFitPoints);
    ASSERT_GE(end - begin, std::min(nb, kMaxFitPoints));
    for (uint32_t k = 0; k < std::min(nb, end - begin); ++k) EXPECT_EQ(t.fit[begin + k], t.nb[t.nb_offsets[i] + k]);
    for (uint32_t k = begin; k < end; ++k) EXPECT_LT(pos[t.fit[k]], i);
    largest = std::max<size_t>(largest, end - begin);
  }
  EXPECT_GE(largest, 8u);  // the second ring adds points on a grid
}

}  // namespace
}  // namespace dcurve
