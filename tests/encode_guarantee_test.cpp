// The encoder's promise, checked by decoding the written bytes: every vertex of every input
// frame within tolerance * L, files shrink as the tolerance loosens, and the in-between
// evaluation has no jumps larger than the tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "corpus/sim/scene.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

std::vector<std::vector<float>> decode_frames(const std::vector<uint8_t>& bytes, uint32_t frames) {
  std::string err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  EXPECT_TRUE(dec) << err;
  std::vector<std::vector<float>> out;
  for (uint32_t f = 0; dec && f < frames; ++f) {
    out.emplace_back(3 * size_t(dec->vertex_count()));
    dec->evaluate(frames > 1 ? double(f) / (frames - 1) : 0.0, out.back().data());
  }
  return out;
}

class Guarantee : public ::testing::TestWithParam<const char*> {};

// Every frame within tolerance at three tolerances; returns the file sizes, tightest first.
std::vector<uint64_t> check_tolerances(const Animation& anim, const std::string& name) {
  std::vector<uint64_t> sizes;
  for (double tol : {1e-4, 1e-3, 1e-2}) {
    EncodeOptions opt;
    opt.tolerance = tol;
    // The grid search (several trial encodes) runs at 1e-3; the others take a fixed grid,
    // which the guarantee does not depend on, to keep CI time down.
    if (tol != 1e-3) opt.grid_refinement = 1.5;
    std::vector<uint8_t> bytes;
    EncodeReport rep;
    std::string err;
    if (!encode_animation(anim, opt, &bytes, &rep, &err)) {
      ADD_FAILURE() << name << ": " << err;
      return sizes;
    }
    // Independent of the encoder's own report: decode through evaluate(t) at frame times.
    ErrorStats e = measure_error(anim, decode_frames(bytes, uint32_t(anim.frames.size())));
    for (size_t f = 0; f < e.max_error_per_frame.size(); ++f)
      EXPECT_LE(e.max_error_per_frame[f], tol) << name << " frame " << f << " tol " << tol;
    EXPECT_NEAR(e.max_error, rep.error.max_error, 1e-12);
    sizes.push_back(bytes.size());
  }
  return sizes;
}

// Size is not asserted here: on a nearly static regular lattice (the first frames of
// cloth-sphere) a tighter grid can happen to align with the lattice and code smaller.
TEST_P(Guarantee, EveryFrameWithinTolerance) {
  if (!have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found";
  check_tolerances(read_corpus_frames(GetParam(), 5, 3), GetParam());
}

// The built-in simulated scenes (shortened): within tolerance, and smaller files as the
// tolerance loosens.
class BuiltinGuarantee : public ::testing::TestWithParam<const char*> {};

TEST_P(BuiltinGuarantee, WithinToleranceAndSizeShrinksAsToleranceLoosens) {
  const Animation anim = test::simulate_builtin(GetParam(), 12);
  std::vector<uint64_t> sizes = check_tolerances(anim, GetParam());
  for (size_t k = 1; k < sizes.size(); ++k) EXPECT_LT(sizes[k], sizes[k - 1]) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Corpus, BuiltinGuarantee,
                         ::testing::Values("rope-small", "cantilever", "neck", "blob", "sheet"));

INSTANTIATE_TEST_SUITE_P(CorpusExt, Guarantee,
                         ::testing::Values("horse-gallop", "chicken-crossing", "elastic-cow", "cloth-sphere", "crane"));

// With a PDE model the frames are still exact to the grid, and between frames the output
// follows the model: it must stay near the input's own in-between motion, not swing away.
// Every motion is kept (the rate control would drop these, which pay for nothing here).
TEST(Guarantee, PdeModelKeepsTheGuaranteeAndSmoothInBetweens) {
  if (!have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found";
  Animation all = read_corpus_frames("horse-gallop", 9);
  Animation even = all;
  even.frames.clear();
  for (size_t f = 0; f < all.frames.size(); f += 2) even.frames.push_back(all.frames[f]);
  const double L = bbox_diagonal(all.frames[0]);
  for (ModelChoice model : {ModelChoice::Pde8, ModelChoice::Pde32}) {
    EncodeOptions opt;
    opt.model = model;
    opt.segment_frames = 2;
    opt.keep_all_motions = true;
    opt.grid_refinement = 1.5;  // the grid is not what this test is about: skip its trials
    std::vector<uint8_t> bytes;
    EncodeReport rep;
    std::string err;
    ASSERT_TRUE(encode_animation(even, opt, &bytes, &rep, &err)) << err;
    EXPECT_LE(rep.error.max_error, opt.tolerance);
    EXPECT_EQ(rep.segments, 2u);
    EXPECT_GT(rep.model_bytes, 0u);
    auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
    ASSERT_TRUE(dec) << err;
    // Odd input frames were never seen by the encoder; the largest frame-to-frame step of
    // the input bounds a plausible in-between's error.
    std::vector<float> xyz(3 * size_t(all.vertex_count));
    for (size_t f = 1; f < all.frames.size(); f += 2) {
      dec->evaluate(double(f) / double(all.frames.size() - 1), xyz.data());
      double worst = 0, step = 0;
      for (size_t i = 0; i < xyz.size(); i += 3) {
        double d2 = 0, s2 = 0;
        for (int a = 0; a < 3; ++a) {
          d2 += std::pow(double(xyz[i + a]) - all.frames[f][i + a], 2);
          s2 += std::pow(double(all.frames[f + 1][i + a]) - all.frames[f - 1][i + a], 2);
        }
        worst = std::max(worst, std::sqrt(d2));
        step = std::max(step, std::sqrt(s2));
      }
      EXPECT_LE(worst, step + opt.tolerance * L) << "frame " << f;
    }
  }
}

// The grid the trial encodes choose gives the same file as that grid given, for any thread
// count: the winning trial stands in for the plain encode when it coded every frame.
TEST(Guarantee, ChosenGridEncodesLikeTheSameGridGiven) {
  const Animation anim = test::simulate_builtin("cantilever", 12);
  EncodeOptions opt;
  std::vector<uint8_t> chosen, given, one_thread;
  EncodeReport rep;
  std::string err;
  ASSERT_TRUE(encode_animation(anim, opt, &chosen, &rep, &err)) << err;
  EXPECT_GT(rep.grid_refinement, 1.01);  // slow, smooth motion: a finer grid than the coarsest
  opt.threads = 1;
  ASSERT_TRUE(encode_animation(anim, opt, &one_thread, nullptr, &err)) << err;
  EXPECT_EQ(one_thread, chosen);
  opt.grid_refinement = rep.grid_refinement;
  EncodeReport given_rep;
  ASSERT_TRUE(encode_animation(anim, opt, &given, &given_rep, &err)) << err;
  EXPECT_EQ(given, chosen);
  EXPECT_DOUBLE_EQ(given_rep.grid_refinement, rep.grid_refinement);
  opt.grid_refinement = 0.5;
  EXPECT_FALSE(encode_animation(anim, opt, &given, nullptr, &err));
}

// Lower efforts encode the grids they name and nothing else: effort 1 is the file of a grid
// 6x finer than the coarsest, effort 2 the smaller of 3x and 8x (the coarser of equals); both
// keep the guarantee. Out-of-range efforts are refused.
TEST(Guarantee, LowerEffortsEncodeTheGridsTheyName) {
  const Animation anim = test::simulate_builtin("cantilever", 12);
  std::string err;
  auto encode = [&](int effort, double refinement, EncodeReport* rep) {
    EncodeOptions opt;
    opt.effort = effort;
    opt.grid_refinement = refinement;
    std::vector<uint8_t> bytes;
    EXPECT_TRUE(encode_animation(anim, opt, &bytes, rep, &err)) << err;
    return bytes;
  };
  EncodeReport rep1, rep2, unused;
  const std::vector<uint8_t> one = encode(1, 0, &rep1), two = encode(2, 0, &rep2);
  const std::vector<uint8_t> at3 = encode(2, 3.0, &unused), at6 = encode(1, 6.0, &unused), at8 = encode(2, 8.0, &unused);
  EXPECT_EQ(one, at6);
  EXPECT_DOUBLE_EQ(rep1.grid_refinement, 6.0);
  EXPECT_EQ(two, at8.size() < at3.size() ? at8 : at3);
  for (const EncodeReport* rep : {&rep1, &rep2}) EXPECT_LE(rep->error.max_error, 1e-3);
  ErrorStats e = measure_error(anim, decode_frames(two, uint32_t(anim.frames.size())));
  EXPECT_LE(e.max_error, 1e-3);
  for (int bad : {0, 4}) {
    EncodeOptions opt;
    opt.effort = bad;
    std::vector<uint8_t> bytes;
    EXPECT_FALSE(encode_animation(anim, opt, &bytes, nullptr, &err));
    EXPECT_NE(err.find("effort"), std::string::npos) << err;
  }
}

TEST(Guarantee, NoJumpsBetweenFrames) {
  if (!have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found";
  Animation anim = read_corpus_frames("cloth-sphere", 4, 10);
  const double tol = 1e-3;
  EncodeOptions opt;
  opt.tolerance = tol;
  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(encode_animation(anim, opt, &bytes, nullptr, &err)) << err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(dec) << err;
  const double L = bbox_diagonal(anim.frames[0]);
  // The largest input step bounds how far x(t) may move between two neighbouring samples.
  double max_step = 0;
  for (size_t f = 1; f < anim.frames.size(); ++f)
    for (size_t i = 0; i < anim.frames[f].size(); i += 3) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(anim.frames[f][i + a] - anim.frames[f - 1][i + a], 2);
      max_step = std::max(max_step, std::sqrt(d2));
    }
  const int samples = 3000;
  const double allowed = max_step * 3.0 / samples * (anim.frames.size() - 1) + tol * L;
  std::vector<float> a(3 * size_t(anim.vertex_count)), b(a.size());
  dec->evaluate(0.0, a.data());
  for (int s = 1; s <= samples; ++s) {
    dec->evaluate(double(s) / samples, b.data());
    double worst = 0;
    for (size_t i = 0; i < a.size(); i += 3) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += std::pow(double(b[i + k]) - a[i + k], 2);
      worst = std::max(worst, std::sqrt(d2));
    }
    ASSERT_LE(worst, allowed) << "jump at t=" << double(s) / samples;
    a.swap(b);
  }
}

TEST(Guarantee, BadAnimationsAreRejected) {
  Animation anim;
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_FALSE(encode_animation(anim, {}, &bytes, nullptr, &err));
  anim.vertex_count = 3;
  anim.faces = {0, 1, 2};
  anim.frames = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 0, 1, 0, 0, 0, NAN, 0}};
  EXPECT_FALSE(encode_animation(anim, {}, &bytes, nullptr, &err));
  EXPECT_NE(err.find("frame 1"), std::string::npos) << err;
  anim.frames[1][7] = 1;
  anim.faces = {0, 1, 5};
  EXPECT_FALSE(encode_animation(anim, {}, &bytes, nullptr, &err));
  anim.faces = {0, 1, 2};
  anim.frames = {{1, 1, 1, 1, 1, 1, 1, 1, 1}};
  EXPECT_FALSE(encode_animation(anim, {}, &bytes, nullptr, &err));  // zero bounding box
}

}  // namespace
}  // namespace dcurve::test
