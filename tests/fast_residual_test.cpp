// The fast residual payload (format 4, format_spec/residual.md section 10): chunks round-trip
// exactly under every predictor kind, damaged tables and streams are rejected, the encoder's
// fast profile writes format 4 files that decode within the tolerance, and the runtime
// decoder reaches any frame in any order as a sequential playback does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

#include "codec/common/container_format.h"
#include "codec/common/crc32.h"
#include "codec/common/fast_residual.h"
#include "codec/common/fast_traversal.h"
#include "codec/common/residual_index.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/fast_residual_decoder.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/rate/fast_plan.h"
#include "test_util.h"

namespace dcurve {
namespace {

using fast_residual::FrameKind;
using test::decoded_max_error;
using test::grid_faces;
using test::refused_or_decodes_as;

constexpr uint32_t kV = 90, kFrames = 6;
constexpr size_t kN = size_t(kV) * 3;
constexpr uint8_t kS = fast_residual::kSpatialFlag, kM = fast_residual::kSmoothFlag | kS;

// A 9 x 10 grid's traversal, or (faces false) the vertex-id chain of a file without faces.
FastTraversal traversal(bool faces = true) {
  return fast_traversal(faces ? grid_faces(9, 10) : std::vector<uint32_t>(), kV);
}

// Frames of smooth motion with sparse noise, and a "model" that predicts them roughly: the
// residuals are mostly small with a few large ones (escapes) and long zero runs.
struct Clip {
  std::vector<int32_t> q, model;
};
Clip make_clip(uint32_t seed) {
  std::mt19937 rng(seed);
  Clip c;
  c.q.resize(kN * kFrames);
  c.model.resize(kN * kFrames);
  for (uint32_t f = 0; f < kFrames; ++f)
    for (size_t i = 0; i < kN; ++i) {
      const int32_t base = int32_t(i * 37 % 1000) - 500 + int32_t(f * f) * int32_t(i % 7);
      const uint32_t roll = rng() % 100;
      const int32_t noise = roll < 80 ? 0 : roll < 97 ? int32_t(rng() % 9) - 4 : int32_t(rng() % 200000) - 100000;
      c.q[f * kN + i] = base + noise;
      c.model[f * kN + i] = base;
    }
  return c;
}

std::vector<uint8_t> chunk_of(const Clip& c, const std::vector<uint8_t>& kinds, bool with_model,
                              const FastTraversal& t = traversal()) {
  return encode_fast_chunk(t, kV, kinds.data(), kFrames, c.q.data(), with_model ? c.model.data() : nullptr);
}

TEST(FastResidual, EveryKindRoundTripsExactly) {
  const Clip c = make_clip(1);
  const std::vector<std::vector<uint8_t>> plans = {{kS, kS, kS, kS, kS, kS},
                                                   {0, 1, 1, 1 | kS, 1, 1},
                                                   {kS, 1, 2, 2, 2 | kS, 2},
                                                   {3, 3, 3 | kS, 3, 3, 3},
                                                   {3, 4, 4, 4 | kS, 4, 4},
                                                   {3 | kS, 1, 2, 4 | kS, 0, 3},
                                                   {kM, 1 | kM, 2 | kM, 2 | kS, kM, 0}};
  for (bool faces : {true, false}) {
    const FastTraversal t = traversal(faces);
    for (const std::vector<uint8_t>& kinds : plans) {
      const bool model = (kinds[0] & 0x0f) == 3;
      const std::vector<uint8_t> bytes = chunk_of(c, kinds, model, t);
      ASSERT_FALSE(bytes.empty());
      std::vector<int32_t> out(c.q.size(), 7);
      std::string err;
      ASSERT_TRUE(decode_fast_chunk(t, kV, bytes.data(), bytes.size(), kFrames, model ? c.model.data() : nullptr,
                                    out.data(), &err))
          << err;
      EXPECT_EQ(out, c.q) << int(kinds[1]) << " faces " << faces;
    }
  }
}

TEST(FastResidual, TheTraversalReachesEveryVertexFromVerticesBeforeIt) {
  for (bool faces : {true, false}) {
    const FastTraversal t = traversal(faces);
    ASSERT_EQ(t.order.size(), kV);
    std::vector<int> position(kV, -1);
    for (size_t i = 0; i < kV; ++i) {
      ASSERT_EQ(position[t.order[i]], -1) << "vertex twice";
      position[t.order[i]] = int(i);
      const int refs = t.type[i] == uint8_t(FastSpatial::Parallelogram) ? 3 : t.type[i];
      for (int j = 0; j < refs; ++j) EXPECT_LT(t.refs[i * 3 + size_t(j)], i) << i;
    }
    if (faces) {  // a regular grid: all but the first few vertices by parallelogram
      const long para = std::count(t.type.begin(), t.type.end(), uint8_t(FastSpatial::Parallelogram));
      EXPECT_GE(para, long(kV) - 12);
    }
  }
}

TEST(FastResidual, AKindThatReadsWhatTheChunkLacksIsNotWritten) {
  const Clip c = make_clip(2);
  EXPECT_TRUE(chunk_of(c, {1, 1, 1, 1, 1, 1}, false).empty());  // frame 0 has no frame before it
  EXPECT_TRUE(chunk_of(c, {0, 2, 2, 2, 2, 2}, false).empty());  // frame 1 has one, not two
  EXPECT_TRUE(chunk_of(c, {3, 3, 3, 3, 3, 3}, false).empty());  // no Model prediction
  EXPECT_TRUE(chunk_of(c, {0x80, 0, 0, 0, 0, 0}, false).empty());  // an unknown flag
  EXPECT_TRUE(chunk_of(c, {0x10, 0x50, 0, 0, 0, 0}, false).empty());  // Fit outside a basis payload
  EXPECT_TRUE(chunk_of(c, {0x20, 0, 0, 0, 0, 0}, false).empty());  // smooth without spatial
}

// Decoding `bytes` fails with an error (and never reads outside them: ASan in CI).
void expect_rejected(const std::vector<uint8_t>& bytes, const Clip& c, const char* what) {
  std::vector<int32_t> out(c.q.size());
  std::string err;
  EXPECT_FALSE(decode_fast_chunk(traversal(), kV, bytes.data(), bytes.size(), kFrames, c.model.data(), out.data(),
                                 &err))
      << what;
  EXPECT_FALSE(err.empty()) << what;
}

TEST(FastResidual, DamagedChunksAreRejected) {
  const Clip c = make_clip(3);
  const std::vector<uint8_t> good = chunk_of(c, {3, 4 | kS, 4, 1, 2 | kS, 4}, true);
  for (size_t cut = 0; cut < good.size(); cut += 7)
    expect_rejected(std::vector<uint8_t>(good.begin(), good.begin() + std::ptrdiff_t(cut)), c, "truncated");
  std::vector<uint8_t> bad = good;
  bad[0] = fast_residual::kFrameKindCount;  // a kind out of range
  expect_rejected(bad, c, "kind out of range");
  bad[0] = 0x43;  // an unknown flag
  expect_rejected(bad, c, "unknown flag");
  bad[0] = 0x23;  // the smooth flag without the spatial flag
  expect_rejected(bad, c, "smooth without spatial");
  bad = good;
  bad[0] = 1;  // frame 0 with a kind that reads the frame before
  expect_rejected(bad, c, "kind not usable");
  bad = good;
  bad[kFrames] ^= 1;  // frame 0's op count: the counts no longer sum to the op stream
  expect_rejected(bad, c, "op counts");
  bad = good;
  bad.push_back(0);  // a byte after the streams
  expect_rejected(bad, c, "trailing byte");
  // A frame checksum: the values decode, but to other values than were coded.
  bad = good;
  bad[kFrames + kFrames + 4 * 2] ^= 0x40;  // past the op counts (each < 128: one byte): frame 2's checksum
  expect_rejected(bad, c, "checksum");
}

TEST(FastResidual, StreamsOutOfRangeAreRejected) {
  // A hand-made chunk of one frame of kV vertices, kind None, raw streams.
  auto chunk = [](const std::vector<uint8_t>& ops, const std::vector<uint8_t>& values, uint32_t checksum) {
    std::vector<uint8_t> b = {0, uint8_t(ops.size())};
    for (int k = 0; k < 4; ++k) b.push_back(uint8_t(checksum >> (8 * k)));
    b.insert(b.end(), {fast_residual::kStreamRaw, uint8_t(ops.size())});
    b.insert(b.end(), ops.begin(), ops.end());
    b.insert(b.end(), {fast_residual::kStreamRaw, uint8_t(values.size())});
    b.insert(b.end(), values.begin(), values.end());
    return b;
  };
  const FastTraversal t = traversal();
  auto decodes = [&t](const std::vector<uint8_t>& bytes) {
    std::vector<int32_t> out(kN);
    std::string err;
    return decode_fast_chunk(t, kV, bytes.data(), bytes.size(), 1, nullptr, out.data(), &err);
  };
  // Vertex 0 axis 0 = 1: op (skip 0, mask 1), value 1 (zigzag 2 -> byte 1).
  std::vector<int32_t> expect(kN, 0);
  expect[0] = 1;
  const uint32_t sum = crc32c(expect.data(), expect.size() * 4);
  EXPECT_TRUE(decodes(chunk({1}, {1}, sum)));
  EXPECT_FALSE(decodes(chunk({1}, {1}, sum ^ 1)));                  // checksum
  EXPECT_FALSE(decodes(chunk({1}, {}, sum)));                       // a value missing
  EXPECT_FALSE(decodes(chunk({1}, {1, 1}, sum)));                   // a value left over
  EXPECT_FALSE(decodes(chunk({uint8_t(2 << 3) | 0}, {}, sum)));     // a long skip past the last vertex
  EXPECT_FALSE(decodes(chunk({uint8_t(31 << 3) | 1, uint8_t(31 << 3) | 1, uint8_t(31 << 3) | 1}, {1, 1, 1}, sum)));
  EXPECT_FALSE(decodes(chunk({1}, {255, 0x80}, sum)));              // an escape that ends early
  EXPECT_FALSE(decodes(chunk({1}, {255, 0xff, 0xff, 0xff, 0xff, 0x7f}, sum)));  // beyond int32
}

// A small cloth whose frames move smoothly: what the fast profile is for.
Animation waving_sheet(uint32_t frames) {
  Animation a;
  const uint32_t W = 14;
  a.vertex_count = W * W;
  a.faces = grid_faces(W, W);
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t v = 0; v < a.vertex_count; ++v) {
      const float x = float(v % W) / W, y = float(v / W) / W;
      xyz.insert(xyz.end(), {x, y, 0.2f * std::sin(3.f * x + 0.2f * float(f)) * std::cos(2.f * y - 0.1f * float(f))});
    }
    a.frames.push_back(xyz);
  }
  return a;
}

std::vector<uint8_t> encode_fast(const Animation& a, int low_rank, uint32_t chunk_frames = 0) {
  EncodeOptions o;
  o.profile = Profile::Fast;
  o.grid_refinement = 2;
  o.low_rank = low_rank;
  o.chunk_frames = chunk_frames;
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(a, o, &bytes, nullptr, &err)) << err;
  return bytes;
}

TEST(FastResidual, FastProfileWritesFormat4WithinTheTolerance) {
  const Animation a = waving_sheet(40);
  for (int low_rank : {-1, 0, 3}) {
    const std::vector<uint8_t> bytes = encode_fast(a, low_rank);
    ASSERT_GE(bytes.size(), 8u);
    EXPECT_EQ(bytes[4] | bytes[5] << 8, kFastFormatVersionMajor) << low_rank;
    EXPECT_LE(decoded_max_error(bytes, a), 1e-3 * (1 + 1e-6)) << low_rank;
    std::string err;
    auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
    ASSERT_TRUE(dec) << err;
    EXPECT_LE(dec->chunk_frames(), 4u) << "40 frames: chunks of at most a tenth, and at least 4";
  }
}

// Chunks of the encoder's length (4 here) and of 16, whose Model frames a seek starts from
// (the frames before them stepped over, not decoded).
class FastSeek : public ::testing::TestWithParam<uint32_t> {};
INSTANTIATE_TEST_SUITE_P(FastResidual, FastSeek, ::testing::Values(0u, 16u));

TEST_P(FastSeek, AnyFrameInAnyOrderDecodesAsSequentialPlayback) {
  const Animation a = waving_sheet(23);
  const std::vector<uint8_t> bytes = encode_fast(a, 3, GetParam());
  std::string err;
  auto seq = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  auto jumps = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(seq && jumps) << err;
  const size_t n = size_t(a.vertex_count) * 3;
  std::vector<std::vector<float>> frames(a.frames.size(), std::vector<float>(n));
  for (uint32_t f = 0; f < frames.size(); ++f) ASSERT_TRUE(seq->evaluate_frame(f, frames[f].data()));
  std::vector<float> x(n);
  for (uint32_t f : {22u, 0u, 13u, 12u, 11u, 3u, 4u, 21u, 7u, 8u, 7u, 1u}) {
    ASSERT_TRUE(jumps->evaluate_frame(f, x.data()));
    EXPECT_EQ(x, frames[f]) << f;
  }
  // Random jumps, back and forth inside and across chunks (the fuzzer found a ring that held
  // one frame twice and then had no slot to decode into).
  std::mt19937 rng(5);
  for (int j = 0; j < 400; ++j) {
    const uint32_t f = rng() % uint32_t(frames.size());
    ASSERT_TRUE(jumps->evaluate_frame(f, x.data())) << f;
    EXPECT_EQ(x, frames[f]) << f;
  }
  // In-betweens across every chunk boundary: frames i and i + 1 from two chunks.
  auto cursor = jumps->make_cursor();
  std::vector<float> y(n);
  for (uint32_t f = 0; f + 1 < frames.size(); ++f) {
    ASSERT_TRUE(cursor->evaluate((f + 0.5) / double(frames.size() - 1), x.data()));
    ASSERT_TRUE(seq->evaluate((f + 0.5) / double(frames.size() - 1), y.data()));
    EXPECT_EQ(x, y) << f;
  }
}

TEST(FastResidual, DamagedFastFilesAreRefusedOrDecodeTheSame) {
  const std::vector<uint8_t> bytes = encode_fast(waving_sheet(12), -1);
  std::string err;
  auto original = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(original) << err;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    std::vector<uint8_t> bad = bytes;
    bad[i] ^= 0x5a;
    EXPECT_TRUE(refused_or_decodes_as(bad, *original)) << "byte " << i;
  }
}

// Frames a seek decodes: from the last frame at or before it that reads no earlier one, or
// its chunk's first.
TEST(FastResidual, SeekFramesCountFromTheLastFrameThatReadsNoEarlierOne) {
  const uint8_t M = uint8_t(FrameKind::Model), P = uint8_t(FrameKind::Previous), D = uint8_t(FrameKind::ModelDelta);
  EXPECT_EQ(fast_seek_frames({M, P, P, M, P}, 8), 3u);
  EXPECT_EQ(fast_seek_frames({M, P, P, P, P, P}, 4), 4u) << "the chunk of frames 4, 5 starts a run";
  EXPECT_EQ(fast_seek_frames({M, D, D, D, D, D, D, D}, 8), 8u);
  EXPECT_EQ(fast_seek_frames({M, uint8_t(P | fast_residual::kSpatialFlag), M}, 8), 2u);
}

// A clip without a model, whose frames read the ones before, in chunks longer than four:
// the planner still keeps every seek within kMaxSeekFrames.
TEST(FastResidual, ThePlannerKeepsSeeksShort) {
  const Animation a = waving_sheet(40);
  const std::vector<uint8_t> bytes = encode_fast(a, 0, 16);
  Model m;
  std::string err;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &m, &err)) << err;
  ResidualIndex index;
  ASSERT_TRUE(read_residual_index(m.residual.payload.data(), m.residual.payload.size(), m.meta.frame_count,
                                  !m.faces.empty(), UINT64_MAX, &index, &err))
      << err;
  std::vector<uint8_t> kinds;
  size_t reading = 0;
  for (size_t c = 0; c < index.chunks.size(); ++c) {
    const uint32_t count = std::min(index.chunk_frames, m.meta.frame_count - uint32_t(c) * index.chunk_frames);
    const uint8_t* chunk = m.residual.payload.data() + index.index_bytes + index.chunks[c].offset;
    kinds.insert(kinds.end(), chunk, chunk + count);  // a chunk starts with its kind bytes
    for (uint32_t k = 0; k < count; ++k) reading += fast_residual::frames_needed(fast_residual::base_kind(chunk[k])) > 0;
  }
  EXPECT_GT(reading, kinds.size() / 2) << "the clip should be one whose frames read earlier ones";
  EXPECT_LE(fast_seek_frames(kinds, index.chunk_frames), kMaxSeekFrames);
}

TEST(FastResidual, ChunkCandidatesKeepRandomAccessCheap) {
  EXPECT_EQ(fast_chunk_candidates(3), std::vector<uint32_t>({3}));
  EXPECT_EQ(fast_chunk_candidates(48), std::vector<uint32_t>({4}));
  EXPECT_EQ(fast_chunk_candidates(600), std::vector<uint32_t>({4, 8, 16, 32}));
  for (uint32_t F : {5u, 48u, 100u, 600u, 5000u})
    for (uint32_t K : fast_chunk_candidates(F)) EXPECT_LE(K, std::max<uint32_t>(4, F / 10)) << F;
}

}  // namespace
}  // namespace dcurve
