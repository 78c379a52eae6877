// The PDE motion model's rate control (encoder/rate/motion_choice.h): motions that predict
// the frames are kept, motions that do not pay become Zero, and `dcurve encode --model pde8`
// never writes a larger file than the encode without a model.
#include <gtest/gtest.h>

#include <random>

#include "codec/compress/container_writer.h"
#include "codec/compress/quantize.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/encoder.h"
#include "encoder/rate/motion_alternatives.h"
#include "encoder/rate/motion_choice.h"
#include "encoder/rate/motion_costs.h"
#include "corpus/sim/scene.h"
#include "test_util.h"

namespace dcurve {
namespace {

constexpr uint32_t kStrips = 4, kHalf = 32, kFrames = 5;
constexpr double kStep = 0.01;

// kStrips disconnected triangle strips of 2 x kHalf vertices, one curve each, whose frames
// are exactly what Pde8 motions with random coefficients predict (plus jitter inside the
// grid cell). Fast oscillation (mu = 10 over 5 frames) leaves temporal prediction nothing
// to work with, so the model is worth far more than its coefficients.
struct Synthetic {
  Model model;  // curves, faces, grid and the generating motions (one segment)
  std::vector<std::vector<float>> frames;
  std::vector<int32_t> rounded;
  Model plain;  // the same frames coded without a motion model
  CodedPayload plain_coded;  // what its payload codes
};

Synthetic make_synthetic(int threads) {
  Synthetic s;
  Model& m = s.model;
  const uint32_t V = kStrips * 2 * kHalf;
  m.meta = {V, kFrames, 30.0, 1e-3, 10.0, ""};
  m.curves.offsets.push_back(0);
  for (uint32_t k = 0; k < kStrips; ++k) {
    const uint32_t base = k * 2 * kHalf;
    for (uint32_t i = 0; i + 1 < kHalf; ++i) {
      const uint32_t a = base + i, b = base + kHalf + i;
      m.faces.insert(m.faces.end(), {a, a + 1, b, a + 1, b + 1, b});
    }
    for (uint32_t i = 0; i < 2 * kHalf; ++i) {
      m.curves.vertices.push_back(base + i);
      m.curves.u.push_back(quantize_curve_u(float(i) / float(2 * kHalf - 1)));
    }
    m.curves.offsets.push_back(uint32_t(m.curves.vertices.size()));
    m.curves.closed.push_back(0);
  }
  m.residual.step = kStep;
  Segment seg;
  seg.last_frame = kFrames - 1;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coeff(-1.0, 1.0), jitter(-0.25, 0.25);
  for (uint32_t c = 0; c < kStrips * 3; ++c) {
    CurveMotion cm;
    cm.basis = Basis::Pde8;
    cm.basis_case = 2;  // trigonometric in time
    cm.time_param = 10.f;
    cm.space_param = 2.f;
    for (int k = 0; k < 8; ++k) cm.coeffs.push_back(float(coeff(rng)));
    quantize_coefficients(&cm, -12);
    seg.motion.push_back(cm);
  }
  m.segments.push_back(seg);

  std::vector<int32_t> prediction;
  std::string err;
  EXPECT_TRUE(stored_model_prediction(m, &prediction, &err)) << err;
  s.rounded = prediction;
  for (uint32_t f = 0; f < kFrames; ++f) {
    s.frames.emplace_back(size_t(V) * 3);
    for (size_t i = 0; i < size_t(V) * 3; ++i)
      s.frames[f][i] = float(grid_to_model(m.residual, int(i % 3), prediction[f * size_t(V) * 3 + i]) +
                             jitter(rng) * kStep);
  }
  s.plain = m;
  s.plain.segments.clear();
  std::vector<int32_t> q = s.rounded;
  ResidualPlanOptions po;
  po.threads = threads;
  const PredictorPlan plan = choose_plan_and_grid(s.plain, s.frames, 0.5 * kStep, &q, {}, po);
  s.plain.residual.payload = encode_residuals(s.plain, q, &plan);
  s.plain_coded = {single_chunk_plan(plan), q};
  return s;
}

// Negates the motions of the odd (first = 1) or even (first = 0) strips: their Model
// prediction is then far off.
void spoil_odd_strips(Model* m, uint32_t first = 1) {
  for (uint32_t c = first; c < kStrips; c += 2)
    for (int a = 0; a < 3; ++a)
      for (float& x : m->segments[0].motion[c * 3 + a].coeffs) x = -x;
}

bool run_choice(Synthetic* s, int threads, MotionChoiceReport* rep) {
  EncodeContext context(s->frames, s->rounded);
  context.snap_distance = 0.5 * kStep;
  context.plan.threads = threads;
  std::string err;
  const bool ok = choose_motions(&s->model, s->plain, s->plain_coded, context, {}, rep, &err);
  EXPECT_TRUE(ok) << err;
  return ok;
}

TEST(MotionChoice, KeepsMotionsThatPredictTheFrames) {
  Synthetic s = make_synthetic(1);
  MotionChoiceReport rep;
  ASSERT_TRUE(run_choice(&s, 1, &rep));
  EXPECT_EQ(rep.fitted, kStrips * 3);
  EXPECT_EQ(rep.kept, kStrips * 3);
  ASSERT_FALSE(s.model.residual.payload.empty());
  EXPECT_LT(write_container(s.model).size(), write_container(s.plain).size());
  std::string err;
  Model back;
  const std::vector<uint8_t> bytes = write_container(s.model);
  EXPECT_TRUE(read_container(bytes.data(), bytes.size(), &back, &err)) << err;
}

TEST(MotionChoice, DropsMotionsThatDoNotPredict) {
  Synthetic s = make_synthetic(1);
  spoil_odd_strips(&s.model);
  MotionChoiceReport rep;
  ASSERT_TRUE(run_choice(&s, 1, &rep));
  EXPECT_EQ(rep.kept, kStrips / 2 * 3);
  for (uint32_t c = 0; c < kStrips; ++c)
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(s.model.segments[0].motion[c * 3 + a].basis, c % 2 ? Basis::Zero : Basis::Pde8) << c << " " << a;
  ASSERT_FALSE(s.model.residual.payload.empty());
  // The payload was coded with the kept motions: the file decodes to the chosen grid values.
  std::vector<int32_t> prediction, q;
  std::string err;
  ASSERT_TRUE(stored_model_prediction(s.model, &prediction, &err)) << err;
  ResidualOptions ro;
  ro.model_prediction = &prediction;
  ASSERT_TRUE(decode_residuals(s.model, &q, &err, ro)) << err;
  for (size_t i = 0; i < q.size(); ++i) ASSERT_LE(std::abs(q[i] - s.rounded[i]), 1) << i;
}

TEST(MotionChoice, DropsEverythingWhenNothingPays) {
  Synthetic s = make_synthetic(1);
  for (CurveMotion& m : s.model.segments[0].motion)
    for (float& x : m.coeffs) x = -x;
  MotionChoiceReport rep;
  ASSERT_TRUE(run_choice(&s, 1, &rep));
  EXPECT_EQ(rep.kept, 0u);
  EXPECT_FALSE(has_motion_model(s.model));
  EXPECT_TRUE(s.model.residual.payload.empty());  // the caller keeps the plain encode
}

TEST(MotionChoice, SameChoiceForAnyThreadCount) {
  Synthetic one = make_synthetic(1), two = make_synthetic(2);
  spoil_odd_strips(&one.model);
  spoil_odd_strips(&two.model);
  MotionChoiceReport r1, r2;
  ASSERT_TRUE(run_choice(&one, 1, &r1));
  ASSERT_TRUE(run_choice(&two, 2, &r2));
  EXPECT_EQ(r1.kept, r2.kept);
  EXPECT_EQ(write_container(one.model), write_container(two.model));
}

// Each strip's good motion comes from a different fitted set; a split into two segments
// with no motions at all is listed first and must lose on the estimate.
TEST(MotionChoice, AlternativesMixTheBestMotionOfEachSlot) {
  Synthetic s = make_synthetic(1);
  Model odd_spoiled = s.model, even_spoiled = s.model;
  spoil_odd_strips(&odd_spoiled, 1);
  spoil_odd_strips(&even_spoiled, 0);
  std::vector<Segment> split(2);
  split[0].last_frame = split[1].first_frame = 2;
  split[1].last_frame = kFrames - 1;
  for (Segment& seg : split) seg.motion.resize(kStrips * 3);
  const std::vector<std::vector<Segment>> fitted = {split, odd_spoiled.segments, even_spoiled.segments};
  std::vector<Segment> chosen;
  MotionAlternativesReport rep;
  std::string err;
  ASSERT_TRUE(choose_motion_alternative(s.model, s.plain, s.plain_coded, fitted, s.rounded, &chosen, &rep, &err)) << err;
  EXPECT_EQ(rep.segmentation, 1u);
  EXPECT_LT(rep.estimated_bytes, rep.baseline_bytes);
  EXPECT_EQ(rep.motions, kStrips * 3);
  EXPECT_EQ(rep.promising, kStrips * 3);
  ASSERT_EQ(chosen.size(), 1u);
  for (size_t k = 0; k < chosen[0].motion.size(); ++k)
    EXPECT_EQ(chosen[0].motion[k].coeffs, s.model.segments[0].motion[k].coeffs) << k;
}

// On a simulated scene the fitted motions do not pay: the encode with --model pde is no
// larger than without a model, decodes within the tolerance and does not depend on threads.
TEST(MotionChoice, PdeEncodeIsNeverLargerThanNone) {
  const Animation anim = test::simulate_builtin("rope-small", 6);
  std::string err;
  EncodeOptions none;
  std::vector<uint8_t> plain_bytes;
  ASSERT_TRUE(encode_animation(anim, none, &plain_bytes, nullptr, &err)) << err;
  std::vector<uint8_t> first;
  for (int threads : {1, 2}) {
    EncodeOptions opt;
    opt.model = ModelChoice::Pde;  // both bases and every automatic segment length
    opt.threads = threads;
    std::vector<uint8_t> bytes;
    EncodeReport rep;
    ASSERT_TRUE(encode_animation(anim, opt, &bytes, &rep, &err)) << err;
    EXPECT_LE(rep.error.max_error, opt.tolerance);
    EXPECT_LE(bytes.size(), plain_bytes.size());
    EXPECT_GT(rep.motions_fitted, 0u);
    EXPECT_LE(rep.motions_kept, rep.motions_fitted);
    if (rep.motions_kept == 0) {
      EXPECT_EQ(bytes, plain_bytes);
    }
    if (first.empty()) first = bytes;
    EXPECT_EQ(bytes, first) << threads << " threads";
  }
}

// The sheet's even frames 0..18 with every PDE motion kept: the block-flag step once rebuilt
// the Model prediction from the in-memory coefficients instead of the stored ones, and one
// grid value rounded otherwise, so the encode failed its own checksum.
TEST(MotionChoice, KeptMotionsEncodeWhereStoredCoefficientsRoundOtherwise) {
  const Animation sim = test::simulate_builtin("sheet", 19);
  Animation anim = sim;
  anim.frames.clear();
  for (size_t f = 0; f < sim.frames.size(); f += 2) anim.frames.push_back(sim.frames[f]);
  EncodeOptions opt;
  opt.model = ModelChoice::Pde;
  opt.keep_all_motions = true;
  opt.low_rank = 0;
  opt.grid_refinement = 4;
  std::vector<uint8_t> bytes;
  EncodeReport rep;
  std::string err;
  ASSERT_TRUE(encode_animation(anim, opt, &bytes, &rep, &err)) << err;
  EXPECT_GT(rep.motions_kept, 0u);
  EXPECT_LE(rep.error.max_error, opt.tolerance);
}

}  // namespace
}  // namespace dcurve
