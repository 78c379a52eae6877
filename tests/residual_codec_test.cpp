// Residual layer: every predictor round-trips bit-exactly and keeps every frame within
// the tolerance after a closed loop through the container; corrupted payloads are
// rejected; the entropy coder reproduces what it coded.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/common/int_coder.h"
#include "codec/common/residual.h"
#include "codec/common/residual_walk.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/range_encoder.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/range_decoder.h"
#include "codec/decompress/residual_decoder.h"
#include "container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/metrics.h"
#include "encoder/rate/block_flags.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {
namespace {

constexpr uint32_t kSheetSide = 9;     // grid sheet of kSheetSide x kSheetSide vertices
constexpr uint32_t kSheetFrames = 10; // frames 6..9 repeat frames 0..3

// A sheet that turns and ripples, then repeats its first poses.
Animation sheet_animation() {
  Animation anim;
  anim.vertex_count = kSheetSide * kSheetSide;
  for (uint32_t i = 0; i + 1 < kSheetSide; ++i)
    for (uint32_t j = 0; j + 1 < kSheetSide; ++j) {
      const uint32_t a = i * kSheetSide + j, b = a + 1, c = a + kSheetSide, d = c + 1;
      anim.faces.insert(anim.faces.end(), {a, b, d, a, d, c});
    }
  for (uint32_t f = 0; f < kSheetFrames; ++f) {
    const double t = f < 6 ? f : f - 6;
    std::vector<float> xyz;
    for (uint32_t i = 0; i < kSheetSide; ++i)
      for (uint32_t j = 0; j < kSheetSide; ++j) {
        const double x = double(j) / (kSheetSide - 1), y = double(i) / (kSheetSide - 1), ang = 0.05 * t;
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
  for (uint32_t v = 0; v < kSheetSide * kSheetSide; ++v) {
    if (v % kSheetSide == 0) c.offsets.push_back(v);
    c.vertices.push_back(v);
    c.u.push_back(float(v % kSheetSide) / (kSheetSide - 1));
  }
  c.offsets.push_back(kSheetSide * kSheetSide);
  c.closed.assign(kSheetSide, 0);
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
  std::vector<uint32_t> stream_bytes;  // per frame, as decoding measured them
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
  ResidualPlan decoded_plan;
  EXPECT_TRUE(decode_residuals(back, &res.decoded, &err, ro, &decoded_plan)) << err;
  if (decoded_plan.chunks.size() == 1) res.stream_bytes = decoded_plan.chunks[0].stream_bytes;
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
          for (size_t k = 2; k < kSheetFrames; ++k) {
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
  for (uint32_t f = 7; f < kSheetFrames; ++f) EXPECT_EQ(r.plan.frames[f].candidates[0][0].r0, f - 6) << "frame " << f;
  // Decoding counts each frame's stream bytes: all of them fit in the payload, and an exact
  // repeat costs a fraction of frame 0, coded from nothing.
  ASSERT_EQ(r.stream_bytes.size(), size_t(kSheetFrames));
  size_t sum = 0;
  for (uint32_t b : r.stream_bytes) sum += b;
  EXPECT_LE(sum, r.payload);
  for (uint32_t f = 7; f < kSheetFrames; ++f) EXPECT_LT(4 * r.stream_bytes[f], r.stream_bytes[0]) << "frame " << f;
}

TEST(ResidualCodec, ClusterLayoutsOfferTheirOwnCountOfSimilarPoses) {
  const Animation anim = sheet_animation();
  for (uint32_t layout_references : {0u, 3u}) {
    SCOPED_TRACE("layout references " + std::to_string(layout_references));
    ResidualPlanOptions po;
    po.kinds = 1u << int(PredictorKind::Reference) | 1u << int(PredictorKind::None);
    po.gop_sizes = {1};
    // The per-frame plan gets no similar pose: only the layout's own count can find the
    // repeats 6 frames back, and the repeats code far smaller, so that layout's plan wins.
    po.extra_references = 0;
    po.cluster_layouts = {{4, 4, layout_references}};
    const LoopResult r = closed_loop(anim, 1e-3, true, po);
    EXPECT_EQ(r.decoded, r.chosen);
    bool repeat_used = false;
    for (uint32_t f = 6; f < kSheetFrames; ++f)
      for (const auto& candidate : r.plan.frames[f].candidates)
        for (const PredictorChoice& c : candidate)
          repeat_used = repeat_used || (c.kind == PredictorKind::Reference && c.r0 == f - 6);
    EXPECT_EQ(repeat_used, layout_references > 0);
  }
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
  for (uint32_t f = 0; f < kSheetFrames; ++f) EXPECT_EQ(r.plan.frames[f].candidates[0][0].kind, PredictorKind::Model);
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
    std::vector<std::vector<float>> frames(kSheetFrames, std::vector<float>(size_t(anim.vertex_count) * 3));
    for (uint32_t f = 0; f < kSheetFrames; ++f) dec->evaluate_frame(f, frames[f].data());
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
  // The default plan's table (frame 0 None, then Reference f - 1, Parallelogram
  // correction), but frame 3's axis 1 refers to frame 4 (zigzag(+1) = 2), not decoded yet.
  const uint8_t none = testing::predictor_byte(0, 2), ref = testing::predictor_byte(1, 2);
  std::vector<std::vector<uint8_t>> records = {{0xff, 0xff, 0xff, 0xff, 0x0f, 1}, {0, 1, none, none, none}};
  for (uint32_t f = 1; f < kSheetFrames; ++f) records.push_back({0, 1, ref, 1, ref, f == 3 ? uint8_t(2) : uint8_t(1), ref, 1});
  m.residual.payload = testing::table_payload(kSheetFrames, true, records);
  std::vector<int32_t> out;
  std::string err;
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  EXPECT_NE(err.find("unavailable frame"), std::string::npos) << err;
}

// Kinds (bit per PredictorKind) used by any (frame, cluster, axis) of a decoded payload.
uint32_t kinds_in_use(const Model& m, const ResidualOptions& ro = {}) {
  ResidualPlan plan;
  std::string err;
  EXPECT_TRUE(decode_predictor_plan(m, &plan, &err, ro, true)) << err;
  uint32_t kinds = 0;
  for (const CodedFrame& coded : coded_frames(plan)) {
    const FramePredictors& fp = *coded.predictors;
    for (uint32_t k = 0; k < cluster_count(m.meta.vertex_count, coded.chunk->cluster_size); ++k)
      for (const PredictorChoice& c : fp.candidates[fp.cluster_candidate.empty() ? 0 : fp.cluster_candidate[k]])
        kinds |= 1u << int(c.kind);
  }
  return kinds;
}

TEST(ResidualCodec, MotionPredictorPerClusterRoundTripsWithinTolerance) {
  const Animation anim = sheet_animation();
  for (bool faces : {true, false})
    for (double tol : {1e-2, 1e-3})
      for (SpatialMode spatial : {SpatialMode::Off, SpatialMode::Mean, SpatialMode::Parallelogram, SpatialMode::Blend,
                                  SpatialMode::Geometric, SpatialMode::Fit}) {
        SCOPED_TRACE(std::string(faces ? "faces" : "curves") + " tol " + std::to_string(tol) + " spatial " +
                     std::to_string(int(spatial)));
        ResidualPlanOptions po;
        // Only Motion can use a reference frame: the motion maps must carry the turning sheet.
        po.kinds = 1u << int(PredictorKind::Motion) | 1u << int(PredictorKind::None);
        po.spatial_modes = 1u << int(spatial);
        po.gop_sizes = {1, 4};
        po.cluster_layouts = {{5, 4}, {27, 1}};
        LoopResult r = closed_loop(anim, tol, faces, po);
        EXPECT_EQ(r.decoded, r.chosen);
        for (double e : r.error.max_error_per_frame) EXPECT_LE(e, tol);
        Model m = grid_model(anim, tol, faces, &r.chosen);
        m.residual.payload = encode_residuals(m, r.decoded, &r.plan);
        // Against raw values (None without correction) the maps must pay; with a spatial
        // correction, None can legitimately win on this smooth sheet.
        if (spatial == SpatialMode::Off) {
          EXPECT_TRUE(kinds_in_use(m) >> int(PredictorKind::Motion) & 1);
        }
      }
}

TEST(ResidualCodec, DefaultClustersRoundTripWithinTolerance) {
  const Animation anim = sheet_animation();
  for (bool faces : {true, false}) {
    ResidualPlanOptions po;
    po.cluster_layouts = {{4, 4}, {16, 1}};
    const LoopResult r = closed_loop(anim, 1e-3, faces, po);
    EXPECT_EQ(r.decoded, r.chosen);
    for (double e : r.error.max_error_per_frame) EXPECT_LE(e, 1e-3);
  }
}

// A hand-made plan: every cluster picks a random candidate among kinds mixed per axis,
// with random motion maps: whatever the encoder would never pick must still round-trip.
PredictorPlan random_cluster_plan(uint32_t V, uint32_t F, std::mt19937& rng) {
  PredictorPlan plan;
  plan.cluster_size = 7;
  plan.motion_block = 3;
  const uint32_t clusters = cluster_count(V, plan.cluster_size), blocks = motion_block_count(V, plan);
  plan.frames.resize(F);
  for (uint32_t f = 0; f < F; ++f) {
    plan.order.push_back(f);
    FramePredictors& fp = plan.frames[f];
    const uint32_t K = f == 0 ? 1 : 1 + rng() % 5;
    for (uint32_t j = 0; j < K; ++j) {
      std::array<PredictorChoice, 3> c;
      for (PredictorChoice& p : c) {
        p.spatial = SpatialMode(rng() % kSpatialModeCount);
        if (f == 0 && uses_geometry(p.spatial)) p.spatial = SpatialMode::Blend;  // no geometry frame yet
        p.kind = f == 0 ? PredictorKind::None : PredictorKind(rng() % 3 == 0 ? 4 : rng() % 3);
        p.r0 = f == 0 ? 0 : uint32_t(rng() % f);
        p.g = f == 0 ? 0 : uint32_t(rng() % f);
        if (p.kind == PredictorKind::Linear) {
          if (f < 2) p.kind = PredictorKind::Motion;
          else p.r1 = (p.r0 + 1 + uint32_t(rng() % (f - 1))) % f;
        }
      }
      fp.candidates.push_back(c);
    }
    if (K > 1)
      for (uint32_t k = 0; k < clusters; ++k) fp.cluster_candidate.push_back(uint8_t(rng() % K));
    fp.transforms.resize(size_t(blocks) * K);
    for (MotionTransform& t : fp.transforms)
      for (MotionRow& row : t.row) {
        for (int32_t& m : row.m) m = int32_t(rng() % 4001) - 2000;
        row.t = int32_t(rng() % 21) - 10;
      }
  }
  return plan;
}

TEST(ResidualCodec, RandomClusterPlansRoundTripBitExactly) {
  const Animation anim = sheet_animation();
  std::mt19937 rng(11);
  for (bool faces : {true, false})
    for (int trial = 0; trial < 10; ++trial) {
      std::vector<int32_t> q;
      Model m = grid_model(anim, 1e-3, faces, &q);
      const PredictorPlan plan = random_cluster_plan(anim.vertex_count, kSheetFrames, rng);
      ASSERT_TRUE(plan_is_valid(plan, kSheetFrames, anim.vertex_count, {}));
      m.residual.payload = encode_residuals(m, q, &plan);
      ASSERT_FALSE(m.residual.payload.empty());
      std::vector<int32_t> out;
      std::string err;
      ASSERT_TRUE(decode_residuals(m, &out, &err)) << err;
      EXPECT_EQ(out, q);
      ResidualPlan back;
      ASSERT_TRUE(decode_predictor_plan(m, &back, &err, {}, true)) << err;
      ASSERT_EQ(back.chunks.size(), 1u);
      for (uint32_t f = 0; f < kSheetFrames; ++f)
        EXPECT_EQ(back.chunks[0].frames[f].cluster_candidate, plan.frames[f].cluster_candidate);
      ResidualPlan with_values;  // the same plan from the decode that also gives the values
      ASSERT_TRUE(decode_residuals(m, &out, &err, {}, &with_values)) << err;
      EXPECT_EQ(out, q);
      for (uint32_t f = 0; f < kSheetFrames; ++f)
        EXPECT_EQ(with_values.chunks[0].frames[f].cluster_candidate, plan.frames[f].cluster_candidate);
      // A traversal the caller supplies (built once, reused) codes and decodes the same bytes.
      const Traversal trav = build_traversal(m);
      ResidualOptions reuse;
      reuse.traversal = &trav;
      EXPECT_EQ(encode_residuals(m, q, &plan, reuse), m.residual.payload);
      std::vector<int32_t> again;
      ASSERT_TRUE(decode_residuals(m, &again, &err, reuse)) << err;
      EXPECT_EQ(again, q);

      // Corrupted copies decode exactly (a flip into an equivalent reference) or are refused.
      const std::vector<uint8_t> good = m.residual.payload;
      for (int flip = 0; flip < 40; ++flip) {
        m.residual.payload = good;
        m.residual.payload[rng() % good.size()] ^= uint8_t(1 + rng() % 255);
        if (decode_residuals(m, &out, &err)) EXPECT_EQ(out, q);
        else EXPECT_FALSE(err.empty());
      }
    }
}

// Payload version 4 flags blocks of zero residuals; version 3 (files 3.0) codes each one.
// Both decode to the same values, and a still clip costs fewer bytes with the flags.
TEST(ResidualCodec, ZeroBlockFlagsChangeBytesNotValues) {
  Animation anim = sheet_animation();
  std::mt19937 rng(5);
  for (bool still : {false, true}) {
    if (still) std::fill(anim.frames.begin(), anim.frames.end(), anim.frames[0]);
    std::vector<int32_t> q;
    Model m = grid_model(anim, 1e-3, true, &q);
    const PredictorPlan plan =
        still ? default_predictor_plan(kSheetFrames) : random_cluster_plan(anim.vertex_count, kSheetFrames, rng);
    ResidualOptions with;
    with.zero_block_flags = true;
    const std::vector<uint8_t> flagged = encode_residuals(m, q, &plan, with), plain = encode_residuals(m, q, &plan);
    ASSERT_FALSE(flagged.empty());
    ASSERT_FALSE(plain.empty());
    EXPECT_EQ(flagged[0], residual_walk::kFormatVersion);
    EXPECT_EQ(plain[0], residual_walk::kOldestFormatVersion);
    for (const std::vector<uint8_t>* payload : {&flagged, &plain}) {
      m.residual.payload = *payload;
      std::vector<int32_t> out;
      std::string err;
      ASSERT_TRUE(decode_residuals(m, &out, &err)) << err;  // the version byte says how to read
      EXPECT_EQ(out, q);
    }
    if (still) {
      EXPECT_LT(flagged.size(), plain.size());
    }
  }
}

// The encoder's last step keeps block flags only where they code smaller: never a larger
// payload, always the same values.
TEST(ResidualCodec, BlockFlagsAreKeptOnlyWhereSmaller) {
  Animation anim = sheet_animation();
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> noise(-0.2f, 0.2f);
  for (bool still : {true, false}) {
    for (std::vector<float>& frame : anim.frames)
      for (size_t i = 0; i < frame.size(); ++i) frame[i] = still ? anim.frames[0][i] : frame[i] + noise(rng);
    std::vector<int32_t> q;
    Model m = grid_model(anim, 1e-3, true, &q);
    m.residual.payload = encode_residuals(m, q);
    const std::vector<uint8_t> before = m.residual.payload;
    std::string err;
    ASSERT_TRUE(use_block_flags(&m, BlockFlagUse::WhenSmaller, &err)) << err;
    EXPECT_LE(m.residual.payload.size(), before.size());
    EXPECT_EQ(m.residual.payload[0], still ? residual_walk::kFormatVersion : residual_walk::kOldestFormatVersion)
        << (still ? "a still clip is mostly zero blocks" : "noise leaves no zero block to flag");
    std::vector<int32_t> out;
    ASSERT_TRUE(decode_residuals(m, &out, &err)) << err;
    EXPECT_EQ(out, q);
  }
}

TEST(ResidualCodec, InvalidCandidatesAndMotionMapsAreRejected) {
  const Animation anim = sheet_animation();
  std::mt19937 rng(5);
  std::vector<int32_t> q;
  Model m = grid_model(anim, 1e-3, true, &q);
  PredictorPlan plan = random_cluster_plan(anim.vertex_count, kSheetFrames, rng);
  // The encoder refuses maps out of the stored range and indices beyond the candidates.
  PredictorPlan bad = plan;
  bad.frames[3].transforms[0].row[1].t = kMaxMotionShift + 1;
  EXPECT_TRUE(encode_residuals(m, q, &bad).empty());
  bad = plan;
  bad.frames[2].cluster_candidate.assign(cluster_count(anim.vertex_count, plan.cluster_size),
                                         uint8_t(bad.frames[2].candidates.size()));
  EXPECT_TRUE(encode_residuals(m, q, &bad).empty());
  // Tables no writer writes: a candidate count of 0 or 17, a cluster size of 0, kind 5.
  std::vector<int32_t> out;
  std::string err;
  const uint8_t none = testing::predictor_byte(0, 2);
  for (uint8_t count : {0, 17}) {
    m.residual.payload = testing::table_payload(kSheetFrames, true, {{7, 3}, {0, count, none, none, none}});
    EXPECT_FALSE(decode_residuals(m, &out, &err));
    EXPECT_NE(err.find("candidate count"), std::string::npos) << err;
  }
  m.residual.payload = testing::table_payload(kSheetFrames, true, {{0, 3}, {0, 1, none, none, none}});
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  EXPECT_NE(err.find("cluster size"), std::string::npos) << err;
  const uint8_t kind5 = testing::predictor_byte(5, 2);
  m.residual.payload = testing::table_payload(kSheetFrames, true, {{7, 3}, {0, 1, kind5, none, none}});
  EXPECT_FALSE(decode_residuals(m, &out, &err));
  EXPECT_NE(err.find("malformed"), std::string::npos) << err;
}

TEST(MotionCompensation, FixedPointPredictionRoundsHalfUpInIntegers) {
  const int64_t centre[3] = {100, -50, 7};
  MotionRow row;
  row.m[0] = 8192;  // x scale 1.5
  row.m[1] = -1;    // a hair of y
  row.t = 3;
  const int32_t x[3] = {101, -50, 1000};
  // 100 + 3 + round((16384 + 8192) * 1 / 16384) = 103 + round(1.5) = 105.
  EXPECT_EQ(motion_prediction(row, 0, centre, x), 105);
  const int32_t y[3] = {99, -49, 7};
  // 103 + round((-24576 - 1) / 16384) = 103 + round(-1.50006) = 103 - 2.
  EXPECT_EQ(motion_prediction(row, 0, centre, y), 101);
  // The identity map reproduces the reference values.
  const MotionRow identity;
  for (int a = 0; a < 3; ++a) EXPECT_EQ(motion_prediction(identity, a, centre, x), x[a]);
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
