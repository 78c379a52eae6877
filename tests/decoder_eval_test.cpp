// What the runtime decoder returns: exact frames, the interpolation rule between them, the
// segment boundary rule, clamping, thread safety, normals and the C ABI.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>
#include <thread>

#include "codec/compress/container_writer.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "decoder/dcurve.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "test_models.h"

namespace dcurve {
namespace {

using testing::grid_position;
using testing::small_model;

std::unique_ptr<Decoder> open(const Model& m, const WriteOptions& opt = {}) {
  std::vector<uint8_t> bytes = write_container(m, opt);
  std::string err;
  auto d = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  EXPECT_TRUE(d) << err;
  return d;
}

TEST(DecoderEval, InputFramesAreTheGridPositionsExactly) {
  const Model m = small_model(5);
  auto d = open(m);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->vertex_count(), 6u);
  EXPECT_EQ(d->frame_count(), 5u);
  EXPECT_EQ(d->face_count(), 4u);
  EXPECT_EQ(d->frame_rate(), 24.0);
  std::vector<float> xyz(18);
  for (uint32_t f = 0; f < 5; ++f) {
    d->evaluate_frame(f, xyz.data());
    for (uint32_t v = 0; v < 6; ++v)
      for (int a = 0; a < 3; ++a) EXPECT_EQ(xyz[v * 3 + a], float(grid_position(m, f, v, a))) << f << " " << v;
  }
}

TEST(DecoderEval, LinearBetweenFramesWithoutAModel) {
  const Model m = small_model(4);
  auto d = open(m);
  ASSERT_TRUE(d);
  std::vector<float> xyz(18);
  for (double t : {0.0, 0.1, 1.0 / 3.0, 0.5, 0.77, 0.999, 1.0}) {
    d->evaluate(t, xyz.data());
    double x = t * 3;
    uint32_t i = std::min(uint32_t(x), 2u);
    double w = x - i;
    for (uint32_t v = 0; v < 6; ++v)
      for (int a = 0; a < 3; ++a) {
        double expect = (1 - w) * grid_position(m, i, v, a) + w * grid_position(m, i + 1, v, a);
        EXPECT_NEAR(xyz[v * 3 + a], expect, 1e-5) << t;
      }
  }
}

TEST(DecoderEval, ClampsTimeAndFrame) {
  auto d = open(small_model(4));
  ASSERT_TRUE(d);
  std::vector<float> got(18), want(18);
  d->evaluate_frame(0, want.data());
  for (double t : {-1.0, -1e-300, std::nan(""), -double(INFINITY)}) {
    d->evaluate(t, got.data());
    EXPECT_EQ(got, want) << t;
  }
  d->evaluate_frame(3, want.data());
  for (double t : {1.0, 1.5, double(INFINITY)}) {
    d->evaluate(t, got.data());
    EXPECT_EQ(got, want) << t;
  }
  d->evaluate_frame(99, got.data());
  EXPECT_EQ(got, want);
}

// Zero-basis segments leave nothing for the model to add, so the output must equal the
// segment-free file everywhere, boundary frames and a zero-length last segment included.
TEST(DecoderEval, ZeroBasisSegmentsMatchPlainInterpolation) {
  auto plain = open(small_model(7));
  auto segmented = open(small_model(7, {0, 2, 3, 6, 6}));
  ASSERT_TRUE(plain && segmented);
  std::vector<float> a(18), b(18);
  for (int k = 0; k <= 60; ++k) {
    double t = k / 60.0;
    plain->evaluate(t, a.data());
    segmented->evaluate(t, b.data());
    EXPECT_EQ(a, b) << t;
  }
}

TEST(DecoderEval, ThreadsGetTheSameFramesAsOneThread) {
  auto d = open(small_model(9, {0, 4, 8}));
  ASSERT_TRUE(d);
  const int N = 2000;
  std::vector<std::vector<float>> serial(N, std::vector<float>(18)), parallel = serial;
  for (int k = 0; k < N; ++k) d->evaluate(k / double(N - 1), serial[k].data());
  auto work = [&](int start) {
    for (int k = start; k < N; k += 2) d->evaluate(k / double(N - 1), parallel[k].data());
  };
  std::thread t0(work, 0), t1(work, 1);
  t0.join();
  t1.join();
  EXPECT_EQ(serial, parallel);
}

TEST(DecoderEval, NormalsAreUnitAndNeedConnectivity) {
  auto d = open(small_model(3));
  ASSERT_TRUE(d);
  std::vector<float> xyz(18), n(18);
  d->evaluate(0.3, xyz.data());
  ASSERT_TRUE(d->compute_normals(xyz.data(), n.data()));
  for (int v = 0; v < 6; ++v) {
    double len = std::sqrt(n[3 * v] * n[3 * v] + n[3 * v + 1] * n[3 * v + 1] + n[3 * v + 2] * n[3 * v + 2]);
    EXPECT_NEAR(len, 1.0, 1e-5) << v;
  }
  WriteOptions no_faces;
  no_faces.connectivity = false;
  auto bare = open(testing::without_faces(small_model(3)), no_faces);
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->faces(), nullptr);
  EXPECT_FALSE(bare->compute_normals(xyz.data(), n.data()));
}

TEST(DecoderEval, CAbiMatchesTheCppApi) {
  const Model m = small_model(4);
  std::vector<uint8_t> bytes = write_container(m);
  dcurve_decoder* d = nullptr;
  char err[128];
  ASSERT_EQ(dcurve_open_memory(bytes.data(), bytes.size(), &d, err, sizeof err), 0) << err;
  EXPECT_EQ(dcurve_vertex_count(d), 6u);
  EXPECT_EQ(dcurve_frame_count(d), 4u);
  ASSERT_EQ(dcurve_face_count(d), 4u);
  EXPECT_EQ(std::vector<uint32_t>(dcurve_faces(d), dcurve_faces(d) + 12), m.faces);
  std::vector<float> xyz(18), n(18);
  dcurve_evaluate_frame(d, 2, xyz.data());
  EXPECT_EQ(xyz[4], float(grid_position(m, 2, 1, 1)));
  EXPECT_EQ(dcurve_compute_normals(d, xyz.data(), n.data()), 0);
  dcurve_close(d);

  dcurve_decoder* bad = reinterpret_cast<dcurve_decoder*>(1);
  char small[8];
  EXPECT_NE(dcurve_open_memory(bytes.data(), 10, &bad, small, sizeof small), 0);
  EXPECT_EQ(bad, nullptr);
  EXPECT_EQ(small[7], '\0');
  EXPECT_EQ(dcurve_vertex_count(nullptr), 0u);
  EXPECT_EQ(dcurve_faces(nullptr), nullptr);
  dcurve_evaluate(nullptr, 0.5, xyz.data());
  EXPECT_NE(dcurve_compute_normals(nullptr, xyz.data(), n.data()), 0);
  EXPECT_EQ(dcurve_open_memory(bytes.data(), bytes.size(), nullptr, err, sizeof err), 2);
  EXPECT_NE(dcurve_open_file("/nonexistent/x.dcrv", &bad, err, sizeof err), 0);
  EXPECT_NE(std::string(err).find("/nonexistent/x.dcrv"), std::string::npos) << err;
}

// Encoder -> file -> decoder: every input frame comes back as the file's quantized model,
// origin + step * q with q decoded from the file, bit for bit, and that model keeps the
// encoder's promise (within tolerance * L of the input; the encoder may pick any grid point
// inside it).
TEST(DecoderEval, EncodedFramesAreTheQuantizedModelBitExact) {
  Animation anim;
  anim.vertex_count = 40;
  for (uint32_t v = 0; v + 2 < 40; ++v) anim.faces.insert(anim.faces.end(), {v, v + 1, v + 2});
  for (int f = 0; f < 6; ++f) {
    std::vector<float> fr(120);
    for (int v = 0; v < 40; ++v) {
      fr[3 * v] = float(v % 8) * 0.1f + 0.01f * f * f;
      fr[3 * v + 1] = float(v / 8) * 0.1f + 0.05f * std::sin(0.3 * f + v);
      fr[3 * v + 2] = 0.02f * f;
    }
    anim.frames.push_back(fr);
  }
  EncodeOptions opt;
  opt.tolerance = 1e-3;
  std::vector<uint8_t> bytes;
  EncodeReport rep;
  std::string err;
  ASSERT_TRUE(encode_animation(anim, opt, &bytes, &rep, &err)) << err;
  Model m;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &m, &err)) << err;
  auto d = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(d) << err;
  // The encoder may pick a motion model here: its residuals are then coded against it.
  std::vector<int32_t> q, prediction;
  ResidualOptions ro;
  if (has_model_prediction(m)) {
    ASSERT_TRUE(model_grid_prediction(m, UINT64_MAX, &prediction, &err)) << err;
    ro.model_prediction = &prediction;
  }
  ASSERT_TRUE(decode_residuals(m, &q, &err, ro)) << err;
  const bool model_free = m.segments.empty();
  std::vector<float> xyz(120);
  for (int f = 0; f < 6; ++f) {
    d->evaluate_frame(f, xyz.data());
    for (int v = 0; v < 40; ++v) {
      double dist2 = 0;
      for (int a = 0; a < 3; ++a) {
        const int i = 3 * v + a;
        const double grid = m.residual.origin[a] + m.residual.step * q[f * 120 + i];
        if (model_free) ASSERT_EQ(xyz[i], float(grid)) << f << " " << i;
        else ASSERT_NEAR(xyz[i], grid, 1e-6 * (1 + std::abs(grid))) << f << " " << i;
        dist2 += (grid - anim.frames[f][i]) * (grid - anim.frames[f][i]);
      }
      EXPECT_LE(std::sqrt(dist2), opt.tolerance * m.meta.diag) << f << " " << v;
    }
  }
}

// PDE segments: the decoder's precomputed tables against the spec's formula evaluated in
// double with codec/common/basis.h directly, at frames, between frames and across boundaries.
TEST(DecoderEval, PdeSegmentsFollowTheSpecFormula) {
  for (FitMode mode : {FitMode::Absolute, FitMode::Displacement}) {
    Model m = small_model(9, {0, 3, 8});
    testing::add_pde_motions(&m, 5);
    for (Segment& s : m.segments) s.mode = mode;
    auto d = open(m);
    ASSERT_TRUE(d);
    std::vector<float> xyz(18);
    for (int k = 0; k <= 64; ++k) {
      const double x = 8.0 * k / 64;
      d->evaluate(x / 8.0, xyz.data());
      for (uint32_t v = 0; v < 6; ++v)
        for (int a = 0; a < 3; ++a) {
          const double ref = testing::reference_position(m, x, v, a);
          EXPECT_NEAR(xyz[v * 3 + a], ref, 2e-5 * (1 + std::abs(ref))) << "x " << x << " v " << v << " a " << a;
        }
    }
    for (uint32_t f = 0; f < 9; ++f) {
      d->evaluate_frame(f, xyz.data());
      for (uint32_t v = 0; v < 6; ++v)
        for (int a = 0; a < 3; ++a) {
          const double grid = grid_position(m, f, v, a);
          // One float rounding of the model plus one of the correction, nothing more.
          EXPECT_NEAR(xyz[v * 3 + a], grid, 4e-7 * (8 + std::abs(grid))) << f;
        }
    }
  }
}

// Approaching a shared boundary frame from either side gives the same positions: each side
// blends corrections computed with its own segment's model.
TEST(DecoderEval, NoJumpAtSegmentBoundaries) {
  Model m = small_model(9, {0, 3, 8});
  testing::add_pde_motions(&m, 9);
  auto d = open(m);
  ASSERT_TRUE(d);
  std::vector<float> before(18), at(18), after(18);
  const double eps = 1e-7;
  d->evaluate((3 - eps) / 8, before.data());
  d->evaluate(3.0 / 8, at.data());
  d->evaluate((3 + eps) / 8, after.data());
  for (int i = 0; i < 18; ++i) {
    EXPECT_NEAR(before[i], at[i], 1e-4) << i;
    EXPECT_NEAR(after[i], at[i], 1e-4) << i;
  }
}

// Without a residual layer the output is the model alone.
TEST(DecoderEval, ModelOnlyFileEvaluatesTheModel) {
  Model m = small_model(5, {0, 4});
  testing::add_pde_motions(&m, 3);
  m.residual = ResidualLayer{};
  std::vector<uint8_t> bytes = write_container(m);
  std::string err;
  auto d = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(d) << err;
  std::vector<float> xyz(18);
  for (double t : {0.0, 0.3, 1.0}) {
    d->evaluate(t, xyz.data());
    for (uint32_t v = 0; v < 6; ++v)
      for (int a = 0; a < 3; ++a) {
        const double ref = testing::segment_model(m, m.segments[0], 4 * t, v, a);
        EXPECT_NEAR(xyz[v * 3 + a], ref, 1e-5 * (1 + std::abs(ref)));
      }
  }
  m.segments[0].mode = FitMode::Displacement;  // needs a rest pose, which needs the residual
  bytes = write_container(m);
  EXPECT_FALSE(Decoder::open_memory(bytes.data(), bytes.size(), &err));
  EXPECT_NE(err.find("rest pose"), std::string::npos) << err;
}

}  // namespace
}  // namespace dcurve
