// In-between rules (format 3.2, format_spec/dcrv.md section 13): the cubics reproduce the
// polynomials they should, stored frames do not move, chunks do not show, the file records
// the rule and refuses a damaged record, and the encoder's choice follows held-out frames.
#include <gtest/gtest.h>

#include <cmath>

#include "codec/common/inbetween.h"
#include "codec/compress/container_writer.h"
#include "codec/decompress/container_reader.h"
#include "container_bytes.h"
#include "decoder/dcurve.h"
#include "decoder/dcurve.hpp"
#include "encoder/rate/inbetween_choice.h"
#include "test_models.h"

namespace dcurve {
namespace {

// Grid values that are a polynomial of the given degree in the frame number, different per
// vertex and axis.
int32_t polynomial_value(int degree, uint32_t f, uint32_t v, int a) {
  const int32_t x = int32_t(f), c0 = int32_t(v * 5 + a) - 7, c1 = int32_t(v % 3) - a, c2 = int32_t(a + 1) - int32_t(v % 2) * 3;
  const int32_t c3 = degree >= 3 ? int32_t(v % 3) - 1 : 0;
  return c0 + c1 * x + (degree >= 2 ? c2 * x * x : 0) + c3 * x * x * x;
}

double polynomial_position(const Model& m, int degree, double x, uint32_t v, int a) {
  const double c0 = double(int32_t(v * 5 + a) - 7), c1 = double(int32_t(v % 3) - a),
               c2 = degree >= 2 ? double(int32_t(a + 1) - int32_t(v % 2) * 3) : 0.0, c3 = degree >= 3 ? double(int32_t(v % 3) - 1) : 0.0;
  return m.residual.origin[a] + m.residual.step * (c0 + c1 * x + c2 * x * x + c3 * x * x * x);
}

// small_model's mesh over F frames of a polynomial motion, in chunks of K frames.
Model polynomial_model(int degree, uint32_t F, uint32_t K, Inbetween rule) {
  Model m = testing::small_model(F);
  std::vector<int32_t> q(size_t(F) * m.meta.vertex_count * 3);
  for (uint32_t f = 0; f < F; ++f)
    for (uint32_t v = 0; v < m.meta.vertex_count; ++v)
      for (int a = 0; a < 3; ++a) q[(size_t(f) * m.meta.vertex_count + v) * 3 + a] = polynomial_value(degree, f, v, a);
  m.residual.payload = encode_residuals(m, q, default_chunked_plan(F, K));
  m.meta.inbetween = rule;
  return m;
}

std::unique_ptr<Decoder> open(const std::vector<uint8_t>& bytes) {
  std::string err;
  auto d = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  EXPECT_TRUE(d) << err;
  return d;
}

// Evaluates at i + w for every interval [i, i + 1] with first <= i and i + 1 <= last
// and compares with the polynomial.
void expect_polynomial(const Model& m, int degree, uint32_t first, uint32_t last) {
  auto d = open(write_container(m));
  ASSERT_TRUE(d);
  const uint32_t F = m.meta.frame_count;
  std::vector<float> xyz(size_t(m.meta.vertex_count) * 3);
  for (uint32_t i = first; i < last; ++i)
    for (double w : {0.125, 0.5, 0.8}) {
      ASSERT_TRUE(d->evaluate((i + w) / double(F - 1), xyz.data()));
      for (uint32_t v = 0; v < m.meta.vertex_count; ++v)
        for (int a = 0; a < 3; ++a) {
          const double want = polynomial_position(m, degree, i + w, v, a);
          EXPECT_NEAR(xyz[v * 3 + a], want, 2e-5 * (1 + std::abs(want))) << "i " << i << " w " << w;
        }
    }
}

TEST(Inbetween, Hermite4IsExactOnCubicMotionAwayFromTheEnds) {
  // Fourth-order tangents need frames f - 2 .. f + 2; chunks of 3 put them in other chunks.
  expect_polynomial(polynomial_model(3, 12, 3, Inbetween::Hermite4), 3, 2, 9);
}

TEST(Inbetween, CatmullRomIsExactOnQuadraticMotionEverywhere) {
  expect_polynomial(polynomial_model(2, 9, 4, Inbetween::CatmullRom), 2, 0, 8);
  expect_polynomial(polynomial_model(2, 9, 4, Inbetween::Hermite4), 2, 0, 8);
}

TEST(Inbetween, LinearMotionIsLinearUnderEveryRule) {
  for (uint8_t r = 0; r < kInbetweenCount; ++r) expect_polynomial(polynomial_model(1, 6, 2, Inbetween(r)), 1, 0, 5);
}

// The chunked test-vector recipe: PDE segments across chunks of 4.
Model chunked_pde_model(uint32_t K) {
  Model m = testing::small_model(10, {0, 5, 9});
  testing::add_pde_motions(&m, 7);
  m.residual.payload = encode_residuals(m, testing::grid(m.meta.vertex_count, 10), default_chunked_plan(10, K));
  return m;
}

TEST(Inbetween, StoredFramesAreTheSameUnderEveryRule) {
  const Model m = chunked_pde_model(4);
  const std::vector<uint8_t> bytes = write_container(m);
  auto linear = open(bytes);
  ASSERT_TRUE(linear);
  const size_t n = size_t(m.meta.vertex_count) * 3;
  for (uint8_t r = 1; r < kInbetweenCount; ++r) {
    auto d = open(bytes);
    ASSERT_TRUE(d);
    d->set_interpolation(Interpolation(r));
    auto cursor = d->make_cursor();
    cursor->set_interpolation(Interpolation(r));
    for (uint32_t f = 0; f < m.meta.frame_count; ++f) {
      std::vector<float> want(n), a(n), b(n), c(n);
      ASSERT_TRUE(linear->evaluate_frame(f, want.data()));
      ASSERT_TRUE(d->evaluate_frame(f, a.data()));
      ASSERT_TRUE(d->evaluate(f / 9.0, b.data()));
      ASSERT_TRUE(cursor->evaluate(f / 9.0, c.data()));
      EXPECT_EQ(a, want) << "frame " << f;
      EXPECT_EQ(b, want) << "frame " << f;
      EXPECT_EQ(c, want) << "frame " << f;
    }
  }
}

TEST(Inbetween, ChunksDoNotChangeTheCubic) {
  auto chunked = open(write_container(chunked_pde_model(3)));
  auto whole = open(write_container(chunked_pde_model(10)));
  ASSERT_TRUE(chunked && whole);
  const size_t n = 18;
  for (uint8_t r = 1; r < kInbetweenCount; ++r) {
    chunked->set_interpolation(Interpolation(r));
    whole->set_interpolation(Interpolation(r));
    // Backwards too: the window must fetch earlier chunks again.
    for (int k = 90; k >= -90; k -= 7) {
      const double t = std::abs(k) / 90.0;
      std::vector<float> a(n), b(n);
      ASSERT_TRUE(chunked->evaluate(t, a.data()));
      ASSERT_TRUE(whole->evaluate(t, b.data()));
      EXPECT_EQ(a, b) << "t " << t;
    }
  }
}

TEST(Inbetween, TheRecordedRuleRoundTrips) {
  for (uint8_t r = 0; r < kInbetweenCount; ++r) {
    Model m = testing::small_model(6);
    m.meta.inbetween = Inbetween(r);
    const std::vector<uint8_t> bytes = write_container(m);
    // File flag bit 1 exactly when META carries the rule (format 3.2).
    EXPECT_EQ((bytes[8] >> 1) & 1, r != 0 ? 1 : 0);
    EXPECT_EQ(bytes[6], 2);  // version_minor
    Model back;
    std::string err;
    ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err)) << err;
    EXPECT_EQ(back.meta.inbetween, Inbetween(r));
    auto d = open(bytes);
    ASSERT_TRUE(d);
    EXPECT_EQ(int(d->interpolation()), int(r));
    dcurve_decoder* c = nullptr;
    ASSERT_EQ(dcurve_open_memory(bytes.data(), bytes.size(), &c, nullptr, 0), DCURVE_OK);
    EXPECT_EQ(dcurve_interpolation(c), int(r));
    EXPECT_EQ(dcurve_set_interpolation(c, 3), DCURVE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(dcurve_set_interpolation(c, -1), DCURVE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(dcurve_set_interpolation(c, DCURVE_INTERPOLATION_HERMITE4), DCURVE_OK);
    dcurve_close(c);
  }
}

bool opens(const std::vector<uint8_t>& bytes) {
  std::string err;
  Model m;
  const bool read = read_container(bytes.data(), bytes.size(), &m, &err);
  const bool decoded = Decoder::open_memory(bytes.data(), bytes.size(), &err) != nullptr;
  EXPECT_EQ(read, decoded);
  return decoded;
}

TEST(Inbetween, AMalformedRecordIsRejected) {
  Model m = testing::small_model(6);
  m.meta.inbetween = Inbetween::CatmullRom;
  testing::RawFile file = testing::split_file(write_container(m));
  ASSERT_EQ(file.sections[0].tag, "META");
  ASSERT_EQ(file.sections[0].flags & 2, 0);  // stored plainly: its last byte is the rule
  ASSERT_TRUE(opens(testing::assemble(file)));

  testing::RawFile bad = file;
  bad.sections[0].stored.back() = kInbetweenCount;  // an unknown rule
  EXPECT_FALSE(opens(testing::assemble(bad)));
  bad.sections[0].stored.back() = 0xff;
  EXPECT_FALSE(opens(testing::assemble(bad)));

  bad = file;
  bad.flags &= ~2u;  // the byte without the flag: META has a byte left over
  EXPECT_FALSE(opens(testing::assemble(bad)));

  bad = file;
  bad.sections[0].stored.pop_back();  // the flag without the byte: META ends early
  bad.sections[0].raw_size = bad.sections[0].stored.size();
  EXPECT_FALSE(opens(testing::assemble(bad)));

  bad = file;
  bad.flags |= 4u;  // a required feature this decoder does not know
  EXPECT_FALSE(opens(testing::assemble(bad)));
}

// F frames of 4 vertices, each moving along x by x_of(f) (and fixed y, z).
std::vector<std::vector<float>> moving_points(uint32_t F, double (*x_of)(uint32_t)) {
  std::vector<std::vector<float>> frames(F);
  for (uint32_t f = 0; f < F; ++f)
    for (uint32_t v = 0; v < 4; ++v) frames[f].insert(frames[f].end(), {float(v + x_of(f)), float(v % 2), float(v / 2)});
  return frames;
}

Model points_model(uint32_t F) {
  Model m;
  m.meta.vertex_count = 4;
  m.meta.frame_count = F;
  m.curves = singleton_curves(4);
  return m;
}

TEST(InbetweenChoice, SmoothMotionGetsACubicAndKinkedMotionStaysLinear) {
  const uint32_t F = 40;
  Model smooth = points_model(F), kinked = points_model(F);
  // A sine of period 16 frames, and a triangle wave that turns at every fourth frame (its
  // held-out frames lie on straight pieces: only linear blending gets them right).
  ASSERT_TRUE(choose_inbetween(&smooth, moving_points(F, [](uint32_t f) { return std::sin(f * 0.3927); }), -1, nullptr));
  ASSERT_TRUE(choose_inbetween(&kinked, moving_points(F, [](uint32_t f) { return std::abs(double(f % 8) - 4.0); }), -1,
                               nullptr));
  EXPECT_NE(smooth.meta.inbetween, Inbetween::Linear);
  EXPECT_EQ(kinked.meta.inbetween, Inbetween::Linear);
  InbetweenScores scores;
  ASSERT_TRUE(score_inbetweens(smooth, moving_points(F, [](uint32_t f) { return std::sin(f * 0.3927); }), &scores, nullptr));
  EXPECT_EQ(scores.held_out_frames, 19u);  // odd frames 1 .. 37 (frame 39 has no even frame after it)
  EXPECT_LT(scores.squared_error[2], scores.squared_error[1]);
  EXPECT_LT(scores.squared_error[1], scores.squared_error[0]);
  // A rule given by the caller is recorded as given.
  ASSERT_TRUE(choose_inbetween(&smooth, moving_points(F, [](uint32_t f) { return std::sin(f * 0.3927); }), 0, nullptr));
  EXPECT_EQ(smooth.meta.inbetween, Inbetween::Linear);
}

}  // namespace
}  // namespace dcurve
