// Residual layer: every predictor round-trips bit-exactly and keeps every frame within
// the tolerance after a closed loop through the container; corrupted payloads are
// rejected; the entropy coder reproduces what it coded.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/container.h"
#include "codec/int_coder.h"
#include "codec/residual.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/metrics.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {
namespace {

constexpr uint32_t kSide = 9;    // grid sheet of kSide x kSide vertices
constexpr uint32_t kFrames = 10; // frames 6..9 repeat frames 0..3

// A sheet that turns and ripples, then repeats its first poses.
Animation sheet_animation() {
  Animation anim;
  anim.vertex_count = kSide * kSide;
  for (uint32_t i = 0; i + 1 < kSide; ++i)
    for (uint32_t j = 0; j + 1 < kSide; ++j) {
      const uint32_t a = i * kSide + j, b = a + 1, c = a + kSide, d = c + 1;
      anim.faces.insert(anim.faces.end(), {a, b, d, a, d, c});
    }
  for (uint32_t f = 0; f < kFrames; ++f) {
    const double t = f < 6 ? f : f - 6;
    std::vector<float> xyz;
    for (uint32_t i = 0; i < kSide; ++i)
      for (uint32_t j = 0; j < kSide; ++j) {
        const double x = double(j) / (kSide - 1), y = double(i) / (kSide - 1), ang = 0.05 * t;
        xyz.push_back(float(std::cos(ang) * x - std::sin(ang) * y + 0.01 * t));
        xyz.push_back(float(std::sin(ang) * x + std::cos(ang) * y));
        xyz.push_back(float(0.1 * std::sin(3 * x + 0.5 * t) * y));
      }
    anim.frames.push_back(xyz);
  }
  return anim;
}

// Rows of the sheet as curves, for the traversal without faces.
Curves row_curves() {
  Curves c;
  for (uint32_t v = 0; v < kSide * kSide; ++v) {
    if (v % kSide == 0) c.offsets.push_back(v);
    c.vertices.push_back(v);
    c.u.push_back(float(v % kSide) / (kSide - 1));
  }
  c.offsets.push_back(kSide * kSide);
  c.closed.assign(kSide, 0);
  return c;
}

// The model and rounded grid values the encoder would start from.
Model grid_model(const Animation& anim, double tol, bool faces, std::vector<int32_t>* q) {
  Model m;
  const double L = bbox_diagonal(anim.frames[0]);
  m.meta = {anim.vertex_count, uint32_t(anim.frames.size()), 30.0, tol, L, ""};
  if (faces) m.faces = anim.faces;
  m.curves = row_curves();
  m.residual.step = 2.0 * tol * L / std::sqrt(3.0) * (1.0 - 1e-3);
  for (int a = 0; a < 3; ++a) m.residual.origin[a] = -2.0;
  q->clear();
  for (const auto& fr : anim.frames)
    for (size_t i = 0; i < fr.size(); ++i)
      q->push_back(int32_t(std::nearbyint((double(fr[i]) - m.residual.origin[i % 3]) / m.residual.step)));
  return m;
}

struct LoopResult {
  std::vector<int32_t> chosen, decoded;
  PredictorPlan plan;
  ErrorStats error;
  size_t payload = 0;
};

// Chooses predictors and grid values, codes, writes and reads the container, decodes.
LoopResult closed_loop(const Animation& anim, double tol, bool faces, const ResidualPlanOptions& po,
                       const ResidualOptions& ro = {}) {
  LoopResult res;
  Model m = grid_model(anim, tol, faces, &res.chosen);
  res.plan = choose_plan_and_grid(m, anim.frames, tol * m.meta.diag, &res.chosen, ro, po);
  m.residual.payload = encode_residuals(m, res.chosen, &res.plan, ro);
  res.payload = m.residual.payload.size();
  const std::vector<uint8_t> file = write_container(m);
  Model back;
  std::string err;
  EXPECT_TRUE(read_container(file.data(), file.size(), &back, &err)) << err;
  EXPECT_TRUE(decode_residuals(back, &res.decoded, &err, ro)) << err;
  std::vector<std::vector<float>> frames(anim.frames.size(), std::vector<float>(size_t(anim.vertex_count) * 3));
  for (size_t i = 0; i < res.decoded.size(); ++i)
    frames[i / frames[0].size()][i % frames[0].size()] = grid_to_model(back.residual, int(i % 3), res.decoded[i]);
  res.error = measure_error(anim, frames);
  return res;
}

struct PredictorCase {
  const char* name;
  PredictorKind kind;
  SpatialMode spatial;
};

TEST(ResidualCodec, EveryPredictorAloneRoundTripsWithinTolerance) {
  const Animation anim = sheet_animation();
  const PredictorCase cases[] = {
      {"delta", PredictorKind::Reference, SpatialMode::Off},
      {"delta+mean", PredictorKind::Reference, SpatialMode::Mean},
      {"delta+parallelogram", PredictorKind::Reference, SpatialMode::Parallelogram},
      {"linear", PredictorKind::Linear, SpatialMode::Off},
      {"linear+parallelogram", PredictorKind::Linear, SpatialMode::Parallelogram},
      {"spatial only", PredictorKind::None, SpatialMode::Parallelogram},
  };
  for (bool faces : {true, false})
    for (double tol : {1e-2, 1e-3})
      for (uint32_t gop : {1u, 4u})
        for (const PredictorCase& c : cases) {
          SCOPED_TRACE(std::string(c.name) + (faces ? " faces" : " curves") + " tol " + std::to_string(tol) +
                       " gop " + std::to_string(gop));
          ResidualPlanOptions po;
          po.kinds = 1u << int(c.kind);
          po.spatial_modes = 1u << int(c.spatial);
          po.gop_sizes = {gop};
          const LoopResult r = closed_loop(anim, tol, faces, po);
          EXPECT_EQ(r.decoded, r.chosen);
          // Linear needs two decoded frames: in time order frame 1 has only one.
          for (size_t k = 2; k < kFrames; ++k) {
            const uint32_t f = r.plan.order[k];
            EXPECT_EQ(r.plan.frames[f].candidates[0][0].kind, c.kind) << "frame " << f;
            EXPECT_EQ(r.plan.frames[f].candidates[0][0].spatial, c.spatial) << "frame " << f;
          }
          for (double e : r.error.max_error_per_frame) EXPECT_LE(e, tol);
        }
}

TEST(ResidualCodec, ReferenceFramesFindTheRepeatedPoses) {
  const Animation anim = sheet_animation();
  ResidualPlanOptions po;
  po.kinds = 1u << int(PredictorKind::Reference) | 1u << int(PredictorKind::None);
  po.gop_sizes = {1};
  const LoopResult r = closed_loop(anim, 1e-3, true, po);
  EXPECT_EQ(r.decoded, r.chosen);
  // Frames 7..9 repeat frames 1..3 exactly: the best reference is 6 frames back.
  for (uint32_t f = 7; f < kFrames; ++f) EXPECT_EQ(r.plan.frames[f].candidates[0][0].r0, f - 6) << "frame " << f;
}

TEST(ResidualCodec, ModelPredictorUsesTheSuppliedGridPrediction) {
  const Animation anim = sheet_animation();
  std::vector<int32_t> q;
  grid_model(anim, 1e-3, true, &q);
  // A "model" that is off by one step on x everywhere: the residuals must undo it.
  std::vector<int32_t> prediction(q);
  for (size_t i = 0; i < prediction.size(); i += 3) prediction[i] += 1;
  ResidualOptions ro;
  ro.model_prediction = &prediction;
  ResidualPlanOptions po;
  po.kinds = 1u << int(PredictorKind::Model);
  const LoopResult r = closed_loop(anim, 1e-3, true, po, ro);
  EXPECT_EQ(r.decoded, r.chosen);
  for (uint32_t f = 0; f < kFrames; ++f) EXPECT_EQ(r.plan.frames[f].candidates[0][0].kind, PredictorKind::Model);
  for (double e : r.error.max_error_per_frame) EXPECT_LE(e, 1e-3);

  // Without the model values the payload cannot be decoded, and says why.
  Model m = grid_model(anim, 1e-3, true, &q);
  m.residual.payload = encode_residuals(m, r.chosen, &r.plan, ro);
  std::vector<int32_t> out;
  std::string err;
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  EXPECT_NE(err.find("model"), std::string::npos) << err;
}

TEST(ResidualCodec, SnappingBeatsRoundingOnTheSameData) {
  const Animation anim = sheet_animation();
  ResidualPlanOptions rounded;
  rounded.snap = false;
  const LoopResult plain = closed_loop(anim, 1e-3, true, rounded);
  const LoopResult snapped = closed_loop(anim, 1e-3, true, ResidualPlanOptions());
  EXPECT_LT(snapped.payload, plain.payload);
  EXPECT_LE(snapped.error.max_error, 1e-3);
}

TEST(ResidualCodec, EncodeAnimationClosedLoopWithAndWithoutConnectivity) {
  const Animation anim = sheet_animation();
  for (bool connectivity : {true, false}) {
    EncodeOptions eo;
    eo.tolerance = 1e-3;
    eo.connectivity = connectivity;
    std::vector<uint8_t> file;
    EncodeReport rep;
    std::string err;
    ASSERT_TRUE(encode_animation(anim, eo, &file, &rep, &err)) << err;
    auto dec = Decoder::open_memory(file.data(), file.size(), &err);
    ASSERT_TRUE(dec) << err;
    EXPECT_EQ(dec->face_count(), connectivity ? anim.faces.size() / 3 : 0u);
    std::vector<std::vector<float>> frames(kFrames, std::vector<float>(size_t(anim.vertex_count) * 3));
    for (uint32_t f = 0; f < kFrames; ++f) dec->evaluate_frame(f, frames[f].data());
    for (double e : measure_error(anim, frames).max_error_per_frame) EXPECT_LE(e, 1e-3);
  }
}

TEST(ResidualCodec, CorruptedPayloadsAreRejected) {
  const Animation anim = sheet_animation();
  std::vector<int32_t> q;
  Model m = grid_model(anim, 1e-3, true, &q);
  m.residual.payload = encode_residuals(m, q);
  const std::vector<uint8_t> good = m.residual.payload;
  std::vector<int32_t> out;
  std::string err;
  ASSERT_TRUE(decode_residuals(m, &out, &err)) << err;
  ASSERT_EQ(out, q);

  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    m.residual.payload = good;
    const size_t at = rng() % good.size();
    m.residual.payload[at] ^= uint8_t(1 + rng() % 255);
    err.clear();
    // A flip may turn a reference into another frame with identical values (the sheet
    // repeats): then the output is still exact. Anything else must be refused.
    if (decode_residuals(m, &out, &err)) EXPECT_EQ(out, q) << "byte " << at;
    else EXPECT_FALSE(err.empty());
  }
  for (size_t cut : {size_t(0), size_t(1), size_t(6), good.size() / 2, good.size() - 1}) {
    m.residual.payload.assign(good.begin(), good.begin() + std::ptrdiff_t(cut));
    EXPECT_FALSE(decode_residuals(m, &out, &err)) << "truncated to " << cut;
  }
  m.residual.payload = good;
  m.residual.payload.push_back(0);
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  // Coded with faces, decoded without: the neighbour structure differs and is refused.
  m.residual.payload = good;
  m.faces.clear();
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  EXPECT_NE(err.find("neighbour"), std::string::npos) << err;
  // Random garbage of every small size.
  m.faces = anim.faces;
  for (size_t n = 0; n < 64; ++n) {
    m.residual.payload.resize(n);
    for (auto& b : m.residual.payload) b = uint8_t(rng());
    EXPECT_FALSE(decode_residuals(m, &out, &err));
  }
}

TEST(ResidualCodec, PlanReferringToLaterFramesIsRejected) {
  const Animation anim = sheet_animation();
  std::vector<int32_t> q;
  Model m = grid_model(anim, 1e-3, true, &q);
  m.residual.payload = encode_residuals(m, q);  // default plan: frame 0 None, then Reference f - 1
  // Header 6 bytes, the cluster size (UINT32_MAX: a 5-byte varint) and the motion block
  // (1 byte); per frame: order
  // varint, candidate count, then per axis a kind byte and, for Reference, the zigzag
  // varint of r0 - f (-1 -> 1).
  const size_t ref_of_frame3_axis1 = 6 + 5 + 1 + (2 + 3) + 2 * (2 + 3 * 2) + 2 + 2 + 1;
  ASSERT_EQ(m.residual.payload[ref_of_frame3_axis1], 1);
  m.residual.payload[ref_of_frame3_axis1] = 3;  // -2 -> frame 1 decoded; use a later frame:
  m.residual.payload[ref_of_frame3_axis1] = 2;  // +1: frame 4, not decoded yet
  std::vector<int32_t> out;
  std::string err;
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  EXPECT_NE(err.find("unavailable frame"), std::string::npos) << err;
}

TEST(AdaptiveIntCoder, ExtremeAndSkewedValuesRoundTrip) {
  std::mt19937_64 rng(3);
  std::vector<std::pair<int, int64_t>> values;
  const int64_t extremes[] = {0, 1, -1, INT32_MAX, INT32_MIN, int64_t(1) << 40, -(int64_t(1) << 40),
                              (int64_t(1) << 41) - 1, -((int64_t(1) << 41) - 1)};
  for (int64_t v : extremes) values.emplace_back(int(rng() % 5), v);
  for (int i = 0; i < 20000; ++i) {
    const int e = int(rng() % 100) < 90 ? 0 : int(rng() % 30);
    const int64_t mag = int64_t(rng() % (uint64_t(1) << e)) + (rng() % 4 == 0 ? 0 : 1);
    values.emplace_back(int(rng() % 5), rng() % 2 ? mag : -mag);
  }
  RangeEncoder enc;
  AdaptiveIntCoder coder(5, 3);
  for (auto& [ctx, v] : values) coder.encode(enc, ctx, ctx % 3, v);
  const std::vector<uint8_t> bytes = enc.finish();
  RangeDecoder dec(bytes.data(), bytes.size());
  AdaptiveIntCoder decoder(5, 3);
  for (auto& [ctx, v] : values) ASSERT_EQ(decoder.decode(dec, ctx, ctx % 3), v);
  EXPECT_TRUE(dec.at_clean_end());
}

TEST(AdaptiveIntCoder, CostsCloseToTheEntropyOfSkewedData) {
  // 95% zeros, 5% +-1: entropy H(0.95) + 0.05 * 1 bit (sign) = 0.336 bit per value.
  std::mt19937 rng(11);
  RangeEncoder enc;
  AdaptiveIntCoder coder(1, 1);
  const int n = 50000;
  for (int i = 0; i < n; ++i) coder.encode(enc, 0, 0, rng() % 100 < 95 ? 0 : (rng() % 2 ? 1 : -1));
  const double bits = 8.0 * double(enc.finish().size());
  EXPECT_LT(bits / n, 0.336 * 1.08);
}

}  // namespace
}  // namespace dcurve
