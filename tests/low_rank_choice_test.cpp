// The low-rank rate control (encoder/rate/low_rank_choice): which model an encode keeps.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/compress/container_writer.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/encoder.h"
#include "encoder/metrics.h"
#include "encoder/rate/grid.h"
#include "encoder/rate/low_rank_choice.h"
#include "encoder/rate/residual_plan.h"
#include "test_util.h"

namespace dcurve {
namespace {

// A W x H grid sheet moving in `modes` fields of random vectors (rough: mesh neighbours do
// not predict them) with random weights per frame (temporal prediction does not either).
Animation rough_modes(uint32_t W, uint32_t H, uint32_t F, uint32_t modes, double amplitude, unsigned seed) {
  Animation anim;
  anim.vertex_count = W * H;
  anim.faces = test::grid_faces(W, H);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  std::vector<double> fields(size_t(modes) * W * H * 3);
  for (double& x : fields) x = amplitude * uniform(rng);
  for (uint32_t f = 0; f < F; ++f) {
    std::vector<double> weights(modes);
    for (double& w : weights) w = f == 0 ? 0 : uniform(rng);
    std::vector<float> xyz;
    for (uint32_t v = 0; v < W * H; ++v) {
      const double rest[3] = {double(v % W) / (W - 1), double(v / W) / (H - 1), 0};
      for (int a = 0; a < 3; ++a) {
        double p = rest[a];
        for (uint32_t m = 0; m < modes; ++m) p += weights[m] * fields[(size_t(m) * W * H + v) * 3 + size_t(a)];
        xyz.push_back(float(p));
      }
    }
    anim.frames.push_back(std::move(xyz));
  }
  return anim;
}

// A finished encode without a low-rank model, as encode_animation hands it to choose_low_rank:
// the model read back from the file, its residual plan and coded grid values, the grid values
// before snapping, the snap distance.
struct PlainEncode {
  Model model;
  ResidualPlan plan;
  std::vector<int32_t> coded, rounded;
  double snap = 0;
};
PlainEncode plain_encode(const Animation& anim, double tolerance) {
  EncodeOptions o;
  o.tolerance = tolerance;
  o.grid_refinement = 1.5;
  o.low_rank = 0;
  std::vector<uint8_t> bytes;
  EncodeReport rep;
  std::string err;
  PlainEncode p;
  EXPECT_TRUE(encode_animation(anim, o, &bytes, &rep, &err)) << err;
  EXPECT_TRUE(read_container(bytes.data(), bytes.size(), &p.model, &err)) << err;
  EXPECT_TRUE(decode_residuals(p.model, &p.coded, &err, {}, &p.plan)) << err;
  EXPECT_TRUE(quantize_to_grid(anim, p.model.residual, &p.rounded, &err)) << err;
  // Inside the encoder's own distance, which leaves room for the decoder's float rounding.
  p.snap = 0.999 * tolerance * bbox_diagonal(anim.frames[0]);
  return p;
}

// Twelve rough modes over 13 moving frames: at the first basis step (0.15 grid steps) the
// section of 12 components outweighs the plain payload, so the first pass stops there; at a
// coarser step such counts pay (here 10, halfway to 8, at step 1: 3,023 bytes against
// 3,090 without the rescue), and only their own trial finds that.
TEST(LowRankChoice, ACountTheFirstBasisStepCutOffGetsATrial) {
  const Animation anim = rough_modes(12, 9, 14, 12, 0.01, 5);
  const PlainEncode p = plain_encode(anim, 1e-3);
  LowRankChoiceOptions lro;
  LowRankChoiceReport with, without;
  std::string err;
  Model rescued = p.model, plain = p.model;
  EncodeContext context(anim.frames, p.rounded);
  context.snap_distance = p.snap;
  ASSERT_TRUE(choose_low_rank(&rescued, {p.plan, p.coded}, context, lro, &with, &err)) << err;
  lro.rescue_cut_counts = false;
  ASSERT_TRUE(choose_low_rank(&plain, {p.plan, p.coded}, context, lro, &without, &err)) << err;
  EXPECT_TRUE(with.rescued);
  EXPECT_FALSE(without.rescued);
  EXPECT_GT(with.kept.components, 0u);
  EXPECT_LT(with.bytes, without.bytes);
  EXPECT_LT(with.bytes, with.bytes_without);
  EXPECT_EQ(with.bytes_without, without.bytes_without);
  // The file kept decodes within the tolerance on every frame.
  const std::vector<uint8_t> bytes = write_container(rescued, {});
  EXPECT_EQ(bytes.size(), with.bytes);
  EXPECT_LE(test::decoded_max_error(bytes, anim), 1e-3);
}

// Following the model a search kept (as an encode of the whole clip follows a trial of its
// middle) screens nothing and keeps the same file; a pick with no model keeps the plain file.
TEST(LowRankChoice, FollowingTheKeptModelGivesTheSameFileWithoutScreening) {
  const Animation anim = rough_modes(12, 9, 14, 12, 0.01, 5);
  const PlainEncode p = plain_encode(anim, 1e-3);
  EncodeContext context(anim.frames, p.rounded);
  context.snap_distance = p.snap;
  std::string err;
  LowRankChoiceReport searched, followed, none;
  Model by_search = p.model, by_follow = p.model, without = p.model;
  ASSERT_TRUE(choose_low_rank(&by_search, {p.plan, p.coded}, context, {}, &searched, &err)) << err;
  ASSERT_GT(searched.kept.components, 0u);
  EXPECT_GT(searched.kept.basis_step, 0.0);
  LowRankChoiceOptions follow;
  follow.follow = &searched.kept;
  ASSERT_TRUE(choose_low_rank(&by_follow, {p.plan, p.coded}, context, follow, &followed, &err)) << err;
  EXPECT_EQ(followed.screened, 0u);
  EXPECT_EQ(followed.trials, 1u);
  EXPECT_EQ(followed.bytes, searched.bytes);
  EXPECT_EQ(write_container(by_follow, {}), write_container(by_search, {}));
  const LowRankPick no_model;
  follow.follow = &no_model;
  ASSERT_TRUE(choose_low_rank(&without, {p.plan, p.coded}, context, follow, &none, &err)) << err;
  EXPECT_EQ(none.kept.components, 0u);
  EXPECT_EQ(none.bytes, none.bytes_without);
  EXPECT_EQ(write_container(without, {}), write_container(p.model, {}));
}

// Whether any chunk of `plan` names more than one geometry frame (a weight table per frame).
bool plans_tables_per_frame(const ResidualPlan& plan) {
  for (const PredictorPlan& chunk : plan.chunks)
    if (geometry_per_frame(chunk)) return true;
  return false;
}

// The full trials plan with the encode's geometry rule (a Fit weight table per frame or one
// per chunk), and a followed pick with the rule its own trial kept.
TEST(LowRankChoice, TrialsPlanWithTheEncodesGeometryRule) {
  const Animation anim = test::simulate_builtin("sheet", 12);  // Fit pays on its smooth cloth
  const PlainEncode p = plain_encode(anim, 1e-3);
  std::string err;
  bool per_frame_kept[2] = {};
  for (bool per_frame : {false, true}) {
    EncodeContext context(anim.frames, p.rounded);
    context.snap_distance = p.snap;
    context.plan.geometry_per_frame = per_frame;
    LowRankChoiceOptions two;
    two.components = 2;  // one trial, no screening
    LowRankChoiceReport rep;
    Model m = p.model;
    CodedResidual kept;
    ASSERT_TRUE(choose_low_rank(&m, {p.plan, p.coded}, context, two, &rep, &err, &kept)) << err;
    ASSERT_GT(rep.kept.components, 0u);
    EXPECT_EQ(plans_tables_per_frame(kept.resi.plan), per_frame);
    EXPECT_EQ(rep.kept.geometry_per_frame, per_frame);
    per_frame_kept[per_frame] = rep.kept.geometry_per_frame;
    // Followed under the other rule, the pick's own rule is planned.
    context.plan.geometry_per_frame = !per_frame;
    LowRankChoiceOptions follow;
    follow.follow = &rep.kept;
    LowRankChoiceReport followed;
    Model again = p.model;
    CodedResidual followed_kept;
    ASSERT_TRUE(choose_low_rank(&again, {p.plan, p.coded}, context, follow, &followed, &err, &followed_kept)) << err;
    EXPECT_EQ(plans_tables_per_frame(followed_kept.resi.plan), per_frame);
  }
  EXPECT_TRUE(per_frame_kept[1]);
}

// A whole clip following a one-table pick tries tables per frame where its encode does: on
// this rope they code over 2 % smaller, and the tried file is no larger than one table's.
TEST(LowRankChoice, FollowedPickTriesTablesPerFrame) {
  const Animation anim = test::simulate_builtin("rope-small", 24);
  const PlainEncode p = plain_encode(anim, 1e-3);
  std::string err;
  EncodeContext context(anim.frames, p.rounded);
  context.snap_distance = p.snap;
  LowRankChoiceOptions two;
  two.components = 2;
  LowRankChoiceReport searched;
  Model m = p.model;
  ASSERT_TRUE(choose_low_rank(&m, {p.plan, p.coded}, context, two, &searched, &err)) << err;
  ASSERT_FALSE(searched.kept.geometry_per_frame);
  // The pick followed under each rule: one table, tables per frame, and tried.
  auto follow = [&](bool try_per_frame, CodedResidual* kept) {
    EncodeContext c = context;
    c.plan.try_geometry_per_frame = try_per_frame;
    LowRankChoiceOptions o;
    o.follow = &searched.kept;
    LowRankChoiceReport rep;
    Model out = p.model;
    EXPECT_TRUE(choose_low_rank(&out, {p.plan, p.coded}, c, o, &rep, &err, kept)) << err;
    return write_container(out, {});
  };
  CodedResidual one, tables, tried;
  const std::vector<uint8_t> one_file = follow(false, &one);
  searched.kept.geometry_per_frame = true;  // the pick's rule is planned
  const std::vector<uint8_t> tables_file = follow(false, &tables);
  searched.kept.geometry_per_frame = false;
  const std::vector<uint8_t> tried_file = follow(true, &tried);
  ASSERT_FALSE(plans_tables_per_frame(one.resi.plan));
  ASSERT_TRUE(plans_tables_per_frame(tables.resi.plan));
  ASSERT_LT(double(tables_file.size()), 0.98 * double(one_file.size()));
  EXPECT_TRUE(plans_tables_per_frame(tried.resi.plan));
  EXPECT_LE(tried_file.size(), one_file.size());
}

}  // namespace
}  // namespace dcurve
