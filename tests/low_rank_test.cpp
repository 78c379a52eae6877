// The low-rank model (LRNK): integer predictions that both sides reproduce, encodes that keep
// the tolerance on every frame, and files with a damaged or absurd LRNK section rejected.
#include <gtest/gtest.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "codec/common/int_coder.h"
#include "codec/common/low_rank.h"
#include "codec/common/validate.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/residual_encoder.h"
#include "codec/compress/range_encoder.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/low_rank_reader.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/metrics.h"
#include "encoder/rate/low_rank.h"
#include "corpus/sim/scene.h"
#include "test_util.h"

namespace dcurve {
namespace {

using testing::RawFile;
using testing::RawSection;

// A W x H sheet bending in two smooth modes with a travelling offset: rank 3 after the mean,
// exactly what a low-rank model captures and temporal deltas do not.
Animation bending_sheet(uint32_t W, uint32_t H, uint32_t F) {
  Animation anim;
  anim.vertex_count = W * H;
  anim.faces = test::grid_faces(W, H);
  for (uint32_t f = 0; f < F; ++f) {
    const double t = 2 * M_PI * f / F;
    std::vector<float> xyz;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const double u = double(x) / (W - 1), w = double(y) / (H - 1);
        const double bend = 0.3 * std::sin(M_PI * u) * std::sin(t) + 0.15 * u * u * std::cos(2 * t);
        xyz.insert(xyz.end(), {float(u + 0.05 * std::sin(t) * w), float(0.5 * w), float(bend + 0.1 * w * std::sin(3 * t))});
      }
    anim.frames.push_back(std::move(xyz));
  }
  return anim;
}

// The 12 x 9 bending sheet's 24 frames on a grid of 2e-4 (values q, frame-major), and a
// model with its counts and faces.
struct SheetOnGrid {
  Model model;
  std::vector<int32_t> q;
  size_t n = 0;  // values per frame
};
SheetOnGrid sheet_on_grid() {
  const Animation anim = bending_sheet(12, 9, 24);
  SheetOnGrid s;
  s.n = size_t(anim.vertex_count) * 3;
  for (const auto& frame : anim.frames)
    for (float x : frame) s.q.push_back(int32_t(std::lround((x + 1.0) / 2e-4)));
  s.model.meta.vertex_count = anim.vertex_count;
  s.model.meta.frame_count = uint32_t(anim.frames.size());
  s.model.faces = anim.faces;
  return s;
}

// The Model predictor's grid values of every frame of m (empty on failure).
std::vector<int32_t> grid_prediction(const Model& m) {
  std::vector<int32_t> prediction;
  std::string err;
  EXPECT_TRUE(model_grid_prediction(m, UINT64_MAX, &prediction, &err)) << err;
  return prediction;
}

// The mean and basis values a decoder reads from m's LRNK basis payload (empty on failure).
std::vector<int32_t> decoded_basis(const Model& m) {
  Model pseudo = m;
  pseudo.meta.frame_count = m.low_rank.components + 1;
  pseudo.residual.payload = m.low_rank.basis_payload;
  std::vector<int32_t> values;
  std::string err;
  EXPECT_TRUE(decode_residuals(pseudo, &values, &err)) << err;
  return values;
}

std::vector<uint8_t> encode(const Animation& anim, int low_rank, EncodeReport* rep, bool first_frame_anchor = true) {
  EncodeOptions o;
  o.tolerance = 1e-3;
  o.low_rank = low_rank;
  o.low_rank_first_frame = first_frame_anchor;
  o.grid_refinement = 1.5;  // the grid search is grid_test's and encode_guarantee_test's
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(anim, o, &bytes, rep, &err)) << err;
  return bytes;
}

// encode(anim, K, ...) read back: the model the file holds, with K components.
Model encoded_model(const Animation& anim, int K, std::vector<uint8_t>* bytes, bool first_frame_anchor = true) {
  EncodeReport rep;
  *bytes = encode(anim, K, &rep, first_frame_anchor);
  Model m;
  std::string err;
  EXPECT_TRUE(read_container(bytes->data(), bytes->size(), &m, &err)) << err;
  EXPECT_EQ(m.low_rank.components, uint32_t(K));
  return m;
}

std::vector<uint8_t> raw_payload(const RawSection& s) {
  if (!(s.flags & 2)) return s.stored;
  std::vector<uint8_t> raw(s.raw_size);
  EXPECT_EQ(ZSTD_decompress(raw.data(), raw.size(), s.stored.data(), s.stored.size()), raw.size());
  return raw;
}

// `bytes` with its LRNK section's raw payload replaced (stored uncompressed, valid CRCs).
std::vector<uint8_t> with_low_rank_payload(const std::vector<uint8_t>& bytes, const std::vector<uint8_t>& raw) {
  RawFile f = testing::split_file(bytes);
  for (RawSection& s : f.sections)
    if (s.tag == "LRNK") s = testing::plain_section("LRNK", true, raw);
  return testing::assemble(f);
}

std::vector<uint8_t> low_rank_payload(const std::vector<uint8_t>& bytes) {
  for (const RawSection& s : testing::split_file(bytes).sections)
    if (s.tag == "LRNK") return raw_payload(s);
  ADD_FAILURE() << "no LRNK section";
  return {};
}

// On a basis step coarser than the grid, the basis rounding is a large part of the model's
// error: coefficients refitted against the rounded basis (quantize_low_rank given the grid
// values) must predict the grid values closer than the PCA weights do (here about 1 %: on a
// rank-3 animation the rounding is noise, which 3 coefficients can hardly follow).
TEST(LowRank, CoefficientsRefittedToTheRoundedBasisPredictCloser) {
  const SheetOnGrid sheet = sheet_on_grid();
  const std::vector<int32_t>& q = sheet.q;
  const GridComponents pca = grid_components(q, sheet.model.meta.frame_count, sheet.n, 3);
  ASSERT_EQ(pca.weights.size(), 3u);
  for (double basis_step : {1.0, 4.0}) {
    double squared[2] = {0, 0};
    for (int refit = 0; refit < 2; ++refit) {
      Model trial = sheet.model;
      ASSERT_TRUE(quantize_low_rank(pca, 3, basis_step, 0, 1, &trial, refit ? &q : nullptr));
      const std::vector<int32_t> prediction = grid_prediction(trial);
      ASSERT_EQ(prediction.size(), q.size());
      for (size_t i = 0; i < q.size(); ++i) squared[refit] += std::pow(double(prediction[i]) - q[i], 2);
    }
    EXPECT_LT(squared[1], squared[0]) << "basis step " << basis_step;
  }
}

// Components around frame 0 (the difference of every frame to it) make frame 0 the stored
// mean: its prediction is exact, and the other frames are predicted as closely as around the
// frame average, since both span the same motion here.
TEST(LowRank, AFirstFrameAnchorPredictsThatFrameExactly) {
  const SheetOnGrid sheet = sheet_on_grid();
  const std::vector<int32_t>& q = sheet.q;
  double largest[2] = {0, 0};  // around the average, around frame 0
  for (uint32_t anchor : {kMeanAnchor, 0u}) {
    const GridComponents pca = grid_components(q, sheet.model.meta.frame_count, sheet.n, 3, anchor);
    ASSERT_EQ(pca.anchor, anchor);
    ASSERT_EQ(pca.weights.size(), 3u);
    Model trial = sheet.model;
    ASSERT_TRUE(quantize_low_rank(pca, 3, 1.0, 0, 1, &trial, &q));
    const std::vector<int32_t> prediction = grid_prediction(trial);
    ASSERT_EQ(prediction.size(), q.size());
    if (anchor == 0) {
      for (size_t i = 0; i < sheet.n; ++i) ASSERT_EQ(prediction[i], q[i]) << i;
    }
    for (size_t i = 0; i < q.size(); ++i)
      largest[anchor == 0] = std::max(largest[anchor == 0], std::fabs(double(prediction[i]) - q[i]));
  }
  EXPECT_LE(largest[1], largest[0] + 1) << "around the average: " << largest[0];
}

// Basis values are chosen within 0.75 basis steps of the exact amplitude (not always the
// nearest integer), towards their spatial prediction; the mean is rounded, since its error
// would repeat in every frame.
TEST(LowRank, BasisValuesStayNearTheirAmplitudesAndTheMeanIsRounded) {
  const SheetOnGrid sheet = sheet_on_grid();
  const std::vector<int32_t>& q = sheet.q;
  Model m = sheet.model;
  const uint32_t F = m.meta.frame_count;
  const size_t n = sheet.n;
  const GridComponents pca = grid_components(q, F, n, 3);
  const double step = 0.5;
  ASSERT_TRUE(quantize_low_rank(pca, 3, step, 1, 1, &m, &q));
  const std::vector<int32_t> values = decoded_basis(m);
  ASSERT_EQ(values.size(), 4 * n);
  size_t moved = 0;
  for (size_t i = 0; i < n; ++i) EXPECT_EQ(values[i], std::nearbyint(pca.mean[i] * 2)) << i;
  for (size_t k = 0; k < 3; ++k)
    for (size_t i = 0; i < n; ++i) {
      const double exact = pca.amplitudes[k][i] / step;
      EXPECT_LE(std::fabs(values[(k + 1) * n + i] - exact), 0.75 + 1e-9) << k << " " << i;
      moved += values[(k + 1) * n + i] != std::lround(exact);
    }
  EXPECT_GT(moved, 0u) << "snapping chose no value other than the nearest";
}

// The memo only saves work: counts up and down and steps interleaved, as the screening
// calls them, give the model a call without it gives, byte for byte. The rate control
// predicts from the values quantize_low_rank returns and recodes the basis from its plan
// instead of decoding the payload: with and without the memo, they must be what a decoder
// decodes, recode to the same payload and predict every frame as the decoder does.
TEST(LowRank, BasisMemoGivesTheSameModelAsCodingAfresh) {
  const SheetOnGrid sheet = sheet_on_grid();
  const std::vector<int32_t>& q = sheet.q;
  const GridComponents pca = grid_components(q, sheet.model.meta.frame_count, sheet.n, 6);
  ASSERT_EQ(pca.weights.size(), 6u);
  BasisMemo memo;
  const std::pair<uint32_t, double> calls[] = {{2, 0.5}, {5, 0.5}, {1, 0.5}, {3, 2.0}, {6, 0.5}, {4, 2.0}, {3, 0.5}};
  for (const auto& [K, step] : calls) {
    Model fresh = sheet.model, memoized = sheet.model;
    CodedPayload fresh_basis, memoized_basis;
    ASSERT_TRUE(quantize_low_rank(pca, K, step, 1, 1, &fresh, &q, nullptr, nullptr, &fresh_basis));
    ASSERT_TRUE(quantize_low_rank(pca, K, step, 1, 1, &memoized, &q, &memo, nullptr, &memoized_basis));
    const std::vector<int32_t>& fresh_values = fresh_basis.values;
    const std::vector<int32_t>& memoized_values = memoized_basis.values;
    EXPECT_EQ(memoized.low_rank.basis_payload, fresh.low_rank.basis_payload) << "K " << K << " step " << step;
    EXPECT_EQ(memoized.low_rank.coeffs, fresh.low_rank.coeffs) << "K " << K << " step " << step;
    EXPECT_EQ(memoized.low_rank.coeff_shifts, fresh.low_rank.coeff_shifts) << "K " << K << " step " << step;
    const std::vector<int32_t> decoded = decoded_basis(fresh);
    ASSERT_EQ(decoded.size(), (K + 1) * sheet.n);
    EXPECT_EQ(fresh_values, decoded) << "K " << K << " step " << step;
    EXPECT_EQ(memoized_values, decoded) << "K " << K << " step " << step;
    EXPECT_EQ(encode_residuals(low_rank_basis_model(fresh), fresh_values, fresh_basis.plan, {}),
              fresh.low_rank.basis_payload)
        << "K " << K << " step " << step;
    std::vector<int32_t> predicted;
    std::string err;
    ASSERT_TRUE(model_grid_prediction(fresh, UINT64_MAX, &predicted, &err)) << err;
    EXPECT_EQ(low_rank_prediction(fresh.low_rank, fresh_values, fresh.meta.frame_count, sheet.n), predicted)
        << "K " << K << " step " << step;
  }
  ASSERT_EQ(memo.entries.size(), 2u);  // one per step
  EXPECT_EQ(memo.entries[0].modes.size(), 6u);
}

TEST(LowRank, RoundShiftIsHalfUpDivision) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    const int64_t x = int64_t(rng() >> 3) - (int64_t(1) << 60);
    const uint32_t s = uint32_t(rng() % 31);
    const __int128 d = __int128(1) << s, n = __int128(x) * 2 + d, den = 2 * d;
    __int128 q = n / den;
    if (n % den != 0 && n < 0) --q;  // floor
    ASSERT_EQ(round_shift(x, s), int64_t(q)) << x << " >> " << s;
  }
  EXPECT_EQ(round_shift(-3, 1), -1);  // -1.5 rounds up
  EXPECT_EQ(round_shift(3, 1), 2);
  EXPECT_EQ(round_shift(-5, 2), -1);
}

// The frame is summed tile by tile: every value, across tile edges and a last partial tile,
// from 32-bit tables, 16-bit pairs in int64 and 16-bit pairs in int32 (coefficients small
// enough; the last case sits at the bound, so its frames take either), is the rounded,
// clamped sum written out in 128 bits.
TEST(LowRank, FrameValuesAreTheDirectSumsInEveryTile) {
  std::mt19937 rng(11);
  const size_t n = 3 * 777;  // tiles of 512 and a partial one; not a multiple of 8
  struct Case {
    int64_t amplitude;
    int32_t coeff;
    uint32_t shift;
  };
  for (const Case& t : {Case{30000, 1 << 20, 20}, Case{kMaxLowRankBasis, 1 << 20, 20}, Case{30000, 300, 10},
                        Case{30000, 7000, 10}}) {
    const int64_t amplitude = t.amplitude;
    LowRankModel lr;
    lr.components = 5;  // odd: the last pair is padded
    lr.shift = t.shift;
    lr.mean_shift = 2;
    std::uniform_int_distribution<int32_t> coeff(-t.coeff, t.coeff), value(-int32_t(amplitude), int32_t(amplitude));
    for (uint32_t i = 0; i < 2 * lr.components; ++i) lr.coeffs.push_back(i == 3 ? 0 : coeff(rng));
    std::vector<int32_t> mean_and_basis((lr.components + 1) * n);
    for (int32_t& v : mean_and_basis) v = value(rng);
    LowRankTables tables;
    tables.assign(mean_and_basis, n);
    ASSERT_EQ(tables.pairs16.empty(), amplitude > INT16_MAX);
    std::vector<int32_t> direct(n), from_tables(n);
    for (uint32_t f = 0; f < 2; ++f) {
      low_rank_frame(lr, f, mean_and_basis.data(), n, direct.data());
      low_rank_frame(lr, f, tables, n, from_tables.data());
      EXPECT_EQ(direct, from_tables);
      for (size_t i = 0; i < n; ++i) {
        __int128 sum = __int128(mean_and_basis[i]) * (__int128(1) << (lr.shift - lr.mean_shift));
        for (uint32_t k = 0; k < lr.components; ++k)
          sum += __int128(lr.coeffs[f * lr.components + k]) * mean_and_basis[(k + 1) * n + i];
        const int64_t want = std::clamp(round_shift(int64_t(sum), lr.shift), -(int64_t(1) << 30), int64_t(1) << 30);
        ASSERT_EQ(direct[i], want) << "frame " << f << " value " << i;
      }
    }
  }
}

TEST(LowRank, ChosenOnALowRankAnimationAndWithinToleranceEveryFrame) {
  const Animation anim = bending_sheet(16, 10, 40);
  EncodeReport with, without;
  const std::vector<uint8_t> auto_bytes = encode(anim, -1, &with);
  const std::vector<uint8_t> off_bytes = encode(anim, 0, &without);
  EXPECT_GT(with.low_rank_components, 0u);
  EXPECT_EQ(without.low_rank_components, 0u);
  EXPECT_LT(auto_bytes.size(), off_bytes.size());
  EXPECT_LE(test::decoded_max_error(auto_bytes, anim), 1e-3);
  const std::vector<uint8_t> forced = encode(anim, 5, &with);
  EXPECT_EQ(with.low_rank_components, 5u);
  EXPECT_LE(test::decoded_max_error(forced, anim), 1e-3);
}

TEST(LowRank, BuiltinSceneWithinToleranceEveryFrame) {
  const Animation anim = test::simulate_builtin("cantilever", 16);
  for (int k : {-1, 3}) {
    EncodeReport rep;
    const std::vector<uint8_t> bytes = encode(anim, k, &rep);
    if (k > 0) {
      EXPECT_EQ(rep.low_rank_components, uint32_t(k));
    }
    EXPECT_LE(test::decoded_max_error(bytes, anim), 1e-3) << "low_rank " << k;
  }
}

// An animation of exactly ten smooth modes: ten is not in the screened list (8, 12), and the
// screening halfway to the best count's neighbours must find it.
TEST(LowRank, FindsACountBetweenTheListedOnes) {
  const uint32_t W = 16, H = 12, F = 48, modes = 10;
  Animation anim = bending_sheet(W, H, F);
  for (uint32_t f = 0; f < F; ++f)
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const double u = double(x) / (W - 1), w = double(y) / (H - 1);
        float* p = &anim.frames[f][3 * (y * W + x)];
        p[0] = float(u);
        p[1] = float(0.5 * w);
        p[2] = 0;
        for (uint32_t m = 0; m < modes; ++m) {
          // Mode m: a smooth field with its own weight over time, none a mix of the others.
          const double field = std::sin(M_PI * (m % 4 + 1) * u + m) * std::cos(M_PI * (m / 4 + 1) * w + 0.5 * m);
          const double weight = std::sin(2 * M_PI * (m + 1) * f / F + 0.7 * m) * 0.08 / (1 + 0.15 * m);
          p[2] += float(field * weight);
        }
      }
  EncodeReport rep;
  const std::vector<uint8_t> bytes = encode(anim, -1, &rep);
  EXPECT_EQ(rep.low_rank_components, modes);
  EXPECT_LE(test::decoded_max_error(bytes, anim), 1e-3);
}

// A regular rest pose that a low-rank motion roughens: the frame average carries the
// roughness, frame 0 none, so components around frame 0 must give the smaller file.
TEST(LowRank, FirstFrameAnchorWinsWhereTheAverageIsRough) {
  const uint32_t W = 12, H = 9, F = 24;
  Animation anim = bending_sheet(W, H, F);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-1, 1);
  std::vector<double> field[2];
  for (auto& fld : field)
    for (uint32_t i = 0; i < W * H * 3; ++i) fld.push_back(0.01 * noise(rng));
  for (uint32_t f = 0; f < F; ++f)
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const uint32_t v = y * W + x;
        const double t = double(f) / F, w0 = std::sin(M_PI * t), w1 = t * t;
        float* p = &anim.frames[f][3 * v];
        const double rest[3] = {double(x) / (W - 1), 0.5 * double(y) / (H - 1), 0};
        for (int a = 0; a < 3; ++a) p[a] = float(rest[a] + w0 * field[0][3 * v + a] + w1 * field[1][3 * v + a]);
      }
  EncodeReport both, average;
  const std::vector<uint8_t> both_bytes = encode(anim, -1, &both);
  const std::vector<uint8_t> average_bytes = encode(anim, -1, &average, false);
  EXPECT_GT(both.low_rank_components, 0u);
  EXPECT_LT(double(both_bytes.size()), 0.9 * double(average_bytes.size())) << average_bytes.size();
  EXPECT_LE(test::decoded_max_error(both_bytes, anim), 1e-3);
  EXPECT_LE(test::decoded_max_error(average_bytes, anim), 1e-3);
}

TEST(LowRank, PredictionIsTheSameOnEveryPath) {
  const Animation anim = bending_sheet(12, 8, 24);
  std::vector<uint8_t> bytes;
  Model m = encoded_model(anim, 3, &bytes);
  ASSERT_EQ(m.low_rank.components, 3u);
  std::string err;
  std::vector<int32_t> p1, p2, p3;
  ASSERT_TRUE(model_grid_prediction(m, UINT64_MAX, &p1, &err)) << err;
  ASSERT_TRUE(model_grid_prediction(m, UINT64_MAX, &p2, &err)) << err;
  EXPECT_EQ(p1, p2);
  // Written again by the writer (the encoder's path) and read back: the same values.
  const std::vector<uint8_t> again = write_container(m);
  EXPECT_EQ(again, bytes);
  Model m2;
  ASSERT_TRUE(read_container(again.data(), again.size(), &m2, &err)) << err;
  ASSERT_TRUE(model_grid_prediction(m2, UINT64_MAX, &p3, &err)) << err;
  EXPECT_EQ(p1, p3);
  // The prediction is close to the decoded grid: the model predicts, it is not noise.
  std::vector<int32_t> q;
  ResidualOptions ro;
  ro.model_prediction = &p1;
  ASSERT_TRUE(decode_residuals(m, &q, &err, ro)) << err;
  double sum2 = 0;
  for (size_t i = 0; i < q.size(); ++i) sum2 += std::pow(double(q[i]) - p1[i], 2);
  EXPECT_LT(std::sqrt(sum2 / double(q.size())), 1.0);
}

TEST(LowRank, DamagedSectionIsRejected) {
  const Animation anim = bending_sheet(10, 6, 16);
  EncodeReport rep;
  const std::vector<uint8_t> bytes = encode(anim, 2, &rep);
  const std::vector<uint8_t> raw = low_rank_payload(bytes);
  ASSERT_FALSE(raw.empty());
  std::string err;
  auto original = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(original) << err;
  for (size_t cut = 0; cut < raw.size(); ++cut) {
    const std::vector<uint8_t> file = with_low_rank_payload(bytes, {raw.begin(), raw.begin() + std::ptrdiff_t(cut)});
    EXPECT_FALSE(Decoder::open_memory(file.data(), file.size(), &err)) << "truncated to " << cut;
  }
  // A change the prediction does not see may decode; then it decodes to the same frames.
  for (size_t i = 0; i < raw.size(); ++i) {
    std::vector<uint8_t> damaged = raw;
    damaged[i] ^= 0x5a;
    ASSERT_TRUE(test::refused_or_decodes_as(with_low_rank_payload(bytes, damaged), *original)) << "byte " << i;
  }
}

// The coefficient differences as svarints (2.0) or range-coded (2.1) decode to the same
// frames; a range-coded stream that does not end exactly, or claims more values than its
// bytes can hold, is rejected.
TEST(LowRank, CoefficientsDecodeTheSameInBothLayouts) {
  const Animation anim = bending_sheet(10, 6, 16);
  std::vector<uint8_t> bytes;
  Model m = encoded_model(anim, 2, &bytes);
  const LowRankModel lr = m.low_rank;
  ASSERT_EQ(lr.components, 2u);
  std::string err;
  // The differences to linear extrapolation, written here independently of the codec.
  std::vector<int64_t> diffs;
  const size_t K = lr.components;
  for (size_t i = 0; i < lr.coeffs.size(); ++i) {
    const int64_t p = i >= 2 * K ? 2 * int64_t(lr.coeffs[i - K]) - lr.coeffs[i - 2 * K] : i >= K ? lr.coeffs[i - K] : 0;
    diffs.push_back(lr.coeffs[i] - p);
  }
  auto payload = [&](bool ranged, const std::vector<uint8_t>& extra) {
    ByteWriter w;
    w.u8(uint8_t(K | (ranged ? 0x80 : 0)));
    w.u8(uint8_t(lr.shift));
    w.u8(uint8_t(lr.mean_shift));
    if (ranged) {
      RangeEncoder enc;
      AdaptiveIntCoder coder(1, 1);
      for (int64_t d : diffs) coder.encode(enc, 0, 0, d);
      std::vector<uint8_t> stream = enc.finish();
      stream.insert(stream.end(), extra.begin(), extra.end());
      w.varint(stream.size());
      w.bytes(stream.data(), stream.size());
    } else {
      for (int64_t d : diffs) w.varint(zigzag_encode(d));
    }
    w.varint(lr.basis_payload.size());
    w.bytes(lr.basis_payload.data(), lr.basis_payload.size());
    return with_low_rank_payload(bytes, w.data());
  };
  auto original = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(original) << err;
  std::vector<float> a(size_t(anim.vertex_count) * 3), b(a.size());
  for (bool ranged : {false, true}) {
    const std::vector<uint8_t> file = payload(ranged, {});
    auto dec = Decoder::open_memory(file.data(), file.size(), &err);
    ASSERT_TRUE(dec) << err << (ranged ? " (range-coded)" : " (svarints)");
    for (uint32_t f = 0; f < dec->frame_count(); ++f) {
      dec->evaluate_frame(f, a.data());
      original->evaluate_frame(f, b.data());
      ASSERT_EQ(a, b) << "frame " << f;
    }
  }
  const std::vector<uint8_t> trailing = payload(true, {0});
  EXPECT_FALSE(read_container(trailing.data(), trailing.size(), &m, &err)) << "a stream with a byte left over";
  // A million coefficients from a one-byte stream: rejected before anything is allocated.
  Model huge;
  huge.meta.frame_count = 1000000;
  const uint8_t tiny[] = {0x81, 4, 0, 1, 0, 0};
  ByteReader r(tiny, sizeof tiny);
  EXPECT_FALSE(parse_low_rank(r, &huge, false));
}

// Per-component coefficient shifts (2.3): an encode of a model with weak components stores
// their coefficients coarser (multiples of 2^s[k], s[k] > 0 somewhere), the section is
// smaller than the same coefficients stored unshifted, and both layouts, written here
// independently of the codec (svarints), decode to the same frames. Components around the
// frame average: the shift rule bounds each component's error, not its bytes, and around
// frame 0 this sheet's shifted svarints come out 6 bytes larger (420 against 414).
TEST(LowRank, CoefficientShiftsShrinkTheSectionAndDecodeTheSame) {
  const Animation anim = bending_sheet(12, 8, 24);
  std::vector<uint8_t> bytes;
  const Model m = encoded_model(anim, 6, &bytes, false);
  const LowRankModel& lr = m.low_rank;
  ASSERT_EQ(lr.coeff_shifts.size(), 6u);
  EXPECT_GT(*std::max_element(lr.coeff_shifts.begin(), lr.coeff_shifts.end()), 0) << "no component was shifted";
  const size_t K = lr.components;
  for (size_t i = 0; i < lr.coeffs.size(); ++i) {
    ASSERT_LE(lr.coeff_shifts[i % K], lr.shift);
    ASSERT_EQ(lr.coeffs[i] % (1 << lr.coeff_shifts[i % K]), 0) << "coefficient " << i;
  }
  // One layout: svarint differences of the values given, to linear extrapolation.
  auto payload = [&](bool shifted) {
    std::vector<int64_t> stored;
    for (size_t i = 0; i < lr.coeffs.size(); ++i)
      stored.push_back(lr.coeffs[i] >> (shifted ? lr.coeff_shifts[i % K] : 0));
    ByteWriter w;
    w.u8(uint8_t(K));
    w.u8(uint8_t(lr.shift));
    w.u8(uint8_t(lr.mean_shift | (shifted ? 0x80 : 0)));
    if (shifted)
      for (uint8_t s : lr.coeff_shifts) w.u8(s);
    for (size_t i = 0; i < stored.size(); ++i) {
      const int64_t p = i >= 2 * K ? 2 * stored[i - K] - stored[i - 2 * K] : i >= K ? stored[i - K] : 0;
      w.varint(zigzag_encode(stored[i] - p));
    }
    w.varint(lr.basis_payload.size());
    w.bytes(lr.basis_payload.data(), lr.basis_payload.size());
    return w.data();
  };
  std::string err;
  auto original = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(original) << err;
  std::vector<float> a(size_t(anim.vertex_count) * 3), b(a.size());
  size_t sizes[2] = {0, 0};
  for (bool shifted : {false, true}) {
    const std::vector<uint8_t> raw = payload(shifted);
    sizes[shifted] = raw.size();
    const std::vector<uint8_t> file = with_low_rank_payload(bytes, raw);
    auto dec = Decoder::open_memory(file.data(), file.size(), &err);
    ASSERT_TRUE(dec) << err << (shifted ? " (shifted)" : " (unshifted)");
    for (uint32_t f = 0; f < dec->frame_count(); ++f) {
      dec->evaluate_frame(f, a.data());
      original->evaluate_frame(f, b.data());
      ASSERT_EQ(a, b) << "frame " << f;
    }
  }
  EXPECT_LT(sizes[1], sizes[0]);
  EXPECT_LT(low_rank_payload(bytes).size(), sizes[0]) << "the encoder's section is not smaller than unshifted svarints";
}

// A shift above S, a stored coefficient that its shift carries past 2^24, and (for the
// writer) a coefficient that is not a multiple of its component's 2^shift are rejected.
TEST(LowRank, BadCoefficientShiftsAreRejected) {
  const Animation anim = bending_sheet(10, 6, 16);
  std::vector<uint8_t> bytes;
  Model m = encoded_model(anim, 2, &bytes);
  const uint8_t S = uint8_t(m.low_rank.shift);
  ASSERT_GE(S, 2);
  auto payload = [&](uint8_t s0, int64_t first) {
    ByteWriter w;
    w.u8(2);
    w.u8(S);
    w.u8(uint8_t(m.low_rank.mean_shift | 0x80));
    w.u8(s0);
    w.u8(0);
    for (size_t i = 0; i < size_t(2) * anim.frames.size(); ++i) w.varint(zigzag_encode(i == 0 ? first : 0));
    w.varint(m.low_rank.basis_payload.size());
    w.bytes(m.low_rank.basis_payload.data(), m.low_rank.basis_payload.size());
    return with_low_rank_payload(bytes, w.data());
  };
  std::string err;
  Model read;
  const std::vector<uint8_t> fine = payload(2, 5);
  EXPECT_TRUE(read_container(fine.data(), fine.size(), &read, &err)) << err;
  EXPECT_EQ(read.low_rank.coeffs[0], 20);
  const std::vector<uint8_t> above = payload(uint8_t(S + 1), 5);
  EXPECT_FALSE(read_container(above.data(), above.size(), &read, &err)) << "shift above S";
  const std::vector<uint8_t> carried = payload(2, (int64_t(1) << 23) + 1);
  EXPECT_FALSE(read_container(carried.data(), carried.size(), &read, &err)) << "2^23 + 1 shifted by 2";
  m.low_rank.coeff_shifts = {1, 0};
  m.low_rank.coeffs[0] = 3;
  EXPECT_FALSE(validate_model(m, &err)) << "odd coefficient with shift 1";
  m.low_rank.coeff_shifts = {1};
  m.low_rank.coeffs[0] = 4;
  EXPECT_FALSE(validate_model(m, &err)) << "one shift for two components";
}

TEST(LowRank, AbsurdFieldsAreRejected) {
  const Animation anim = bending_sheet(10, 6, 16);
  EncodeReport rep;
  const std::vector<uint8_t> bytes = encode(anim, 2, &rep);
  const std::vector<uint8_t> raw = low_rank_payload(bytes);
  ASSERT_GE(raw.size(), 3u);
  Model m;
  std::string err;
  auto rejected = [&](std::vector<uint8_t> payload, const char* what) {
    const std::vector<uint8_t> file = with_low_rank_payload(bytes, payload);
    EXPECT_FALSE(read_container(file.data(), file.size(), &m, &err)) << what;
  };
  for (uint8_t K : {0, 65, 255}) {
    std::vector<uint8_t> p = raw;
    p[0] = K;
    rejected(p, "component count");
  }
  std::vector<uint8_t> p = raw;
  p[1] = 31;
  rejected(p, "shift above 30");
  p = raw;
  p[2] = uint8_t(p[1] + 1);
  rejected(p, "mean shift above shift");
  // A coefficient far outside +-2^24: the first one, written as a 5-byte varint (svarint
  // layout: bit 7 of the first byte clear).
  const uint8_t K = raw[0] & 0x7f;
  p = {K, raw[1], raw[2], 0x80, 0x80, 0x80, 0x80, 0x01};
  rejected(p, "coefficient out of range");
  // More coefficients than bytes, and a basis payload longer than the section.
  rejected({64, 10, 0, 0, 0}, "counts beyond the payload");
  p = {K, raw[1], raw[2]};
  for (size_t i = 0; i < size_t(K) * anim.frames.size(); ++i) p.push_back(0);
  p.insert(p.end(), {0xff, 0xff, 0xff, 0xff, 0x0f});
  rejected(p, "basis payload size");
  // An unknown reader must not skip it: the REQUIRED flag is set.
  for (const RawSection& s : testing::split_file(bytes).sections)
    if (s.tag == "LRNK") {
      EXPECT_TRUE(s.flags & 1);
    }
  // A low-rank model and PDE motions together are invalid.
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &m, &err)) << err;
  m.segments = {Segment{0, m.meta.frame_count - 1, FitMode::Absolute, {}}};
  m.segments[0].motion.resize(size_t(m.curves.curve_count()) * 3);
  m.segments[0].motion[0].basis = Basis::Pde8;
  m.segments[0].motion[0].coeffs.assign(8, 0.f);
  EXPECT_FALSE(validate_model(m, &err));
}

}  // namespace
}  // namespace dcurve
