// LRNK's packed differences (format 4, format_spec/dcrv.md section 10, Z = 1): the fast
// profile writes them, they decode to the same frames as the range-coded form, and every
// rule of the packed form is enforced.
#include <gtest/gtest.h>
#include <zstd.h>

#include <cmath>
#include <functional>

#include "codec/common/bytes.h"
#include "codec/common/container_format.h"
#include "codec/compress/low_rank_writer.h"
#include "codec/decompress/container_reader.h"
#include "container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "test_util.h"

namespace dcurve {
namespace low_rank_packed {  // named: the sanitized build batches test files together

constexpr uint8_t kPackedBit = 0x20;  // bit 5 of LRNK's third byte

// A sheet waving in two travelling modes: low rank, so both profiles keep an LRNK model.
Animation waving(uint32_t W, uint32_t F) {
  Animation a;
  a.vertex_count = W * W;
  a.faces = test::grid_faces(W, W);
  for (uint32_t f = 0; f < F; ++f) {
    std::vector<float> xyz;
    const double t = 2 * M_PI * f / F;
    for (uint32_t v = 0; v < a.vertex_count; ++v) {
      const double x = double(v % W) / W, y = double(v / W) / W;
      xyz.insert(xyz.end(), {float(x), float(y), float(0.2 * std::sin(3 * x + t) * std::cos(2 * y) + 0.1 * x * std::cos(2 * t))});
    }
    a.frames.push_back(xyz);
  }
  return a;
}

std::vector<uint8_t> encode(const Animation& a, Profile profile) {
  EncodeOptions o;
  o.profile = profile;
  o.grid_refinement = 2;
  o.low_rank = 2;
  return test::encoded(a, o);
}

Model read(const std::vector<uint8_t>& bytes) {
  Model m;
  std::string why;
  EXPECT_TRUE(read_container(bytes.data(), bytes.size(), &m, &why)) << why;
  return m;
}

std::vector<uint8_t> lrnk_payload(const std::vector<uint8_t>& bytes) {
  for (const testing::RawSection& s : testing::split_file(bytes).sections)
    if (s.tag == "LRNK") {
      if (!(s.flags & 2)) return s.stored;
      std::vector<uint8_t> raw(s.raw_size);
      EXPECT_EQ(ZSTD_decompress(raw.data(), raw.size(), s.stored.data(), s.stored.size()), raw.size());
      return raw;
    }
  ADD_FAILURE() << "no LRNK section";
  return {};
}

std::vector<uint8_t> with_lrnk_payload(const std::vector<uint8_t>& bytes, const std::vector<uint8_t>& raw) {
  testing::RawFile f = testing::split_file(bytes);
  for (testing::RawSection& s : f.sections)
    if (s.tag == "LRNK") s = testing::plain_section("LRNK", true, raw);
  return testing::assemble(f);
}

// How a test bends the packed stream of the coefficient differences.
struct Packing {
  int64_t raw_size_change = 0;        // added to the declared raw_size
  std::vector<uint8_t> extra_varints;  // appended to the svarints before compressing
  size_t cut_stored = 0;               // bytes cut from the end of the zstd frame
  bool ranged_bit = false;             // R set beside Z
};

// m's LRNK payload packed, written here from the spec independently of the codec's writer.
std::vector<uint8_t> packed_payload(const Model& m, const Packing& p) {
  const LowRankModel& lr = m.low_rank;
  const size_t K = lr.components;
  ByteWriter varints;
  std::vector<int64_t> stored(lr.coeffs.size());
  for (size_t i = 0; i < stored.size(); ++i) stored[i] = lr.coeffs[i] >> (lr.coeff_shifts.empty() ? 0 : lr.coeff_shifts[i % K]);
  for (size_t i = 0; i < stored.size(); ++i) {
    const int64_t pred = i >= 2 * K ? 2 * stored[i - K] - stored[i - 2 * K] : i >= K ? stored[i - K] : 0;
    varints.varint(zigzag_encode(stored[i] - pred));
  }
  varints.bytes(p.extra_varints.data(), p.extra_varints.size());
  const std::vector<uint8_t>& raw = varints.data();
  std::vector<uint8_t> z(ZSTD_compressBound(raw.size()));
  z.resize(ZSTD_compress(z.data(), z.size(), raw.data(), raw.size(), 3));
  z.resize(z.size() - p.cut_stored);
  ByteWriter w;
  w.u8(uint8_t(K | (p.ranged_bit ? 0x80 : 0)));
  w.u8(uint8_t(lr.shift));
  w.u8(uint8_t(lr.mean_shift | kPackedBit | (lr.coeff_shifts.empty() ? 0 : 0x80)));
  for (uint8_t s : lr.coeff_shifts) w.u8(s);
  w.varint(uint64_t(int64_t(raw.size()) + p.raw_size_change));
  w.varint(z.size());
  w.bytes(z.data(), z.size());
  w.varint(lr.basis_payload.size());
  w.bytes(lr.basis_payload.data(), lr.basis_payload.size());
  return std::move(w.data());
}

bool same_frames(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  std::string err;
  auto x = Decoder::open_memory(a.data(), a.size(), &err), y = Decoder::open_memory(b.data(), b.size(), &err);
  if (!x || !y || x->frame_count() != y->frame_count()) return false;
  std::vector<float> p(size_t(x->vertex_count()) * 3), q(p.size());
  for (uint32_t f = 0; f < x->frame_count(); ++f)
    if (!x->evaluate_frame(f, p.data()) || !y->evaluate_frame(f, q.data()) || p != q) return false;
  return true;
}

bool opens(const std::vector<uint8_t>& bytes) {
  std::string err;
  return Decoder::open_memory(bytes.data(), bytes.size(), &err) != nullptr;
}

// The fast profile packs; the same model written range-coded (as a 3.x file would) in the same
// file decodes to the same frames, and so does a packed payload written from the spec here.
TEST(LowRankPacked, FastFilesPackAndDecodeAsTheRangeCodedForm) {
  const std::vector<uint8_t> fast = encode(waving(9, 30), Profile::Fast);
  ASSERT_EQ(fast[4] | fast[5] << 8, kFastFormatVersionMajor);
  const std::vector<uint8_t> payload = lrnk_payload(fast);
  ASSERT_GE(payload.size(), 3u);
  EXPECT_TRUE(payload[2] & kPackedBit) << "a format 4 file's LRNK is packed";
  EXPECT_FALSE(payload[0] & 0x80) << "never range-coded beside";
  Model m = read(fast);
  ASSERT_EQ(m.low_rank.components, 2u);
  ASSERT_TRUE(m.low_rank.poses.empty()) << "packed_payload writes no poses";
  EXPECT_TRUE(same_frames(fast, with_lrnk_payload(fast, packed_payload(m, {}))));
  Model unpacked = m;
  unpacked.residual.payload.clear();  // not a format 4 model: the writer range-codes or uses svarints
  const std::vector<uint8_t> plain = low_rank_bytes(unpacked);
  ASSERT_FALSE(plain[2] & kPackedBit);
  EXPECT_TRUE(same_frames(fast, with_lrnk_payload(fast, plain)));
}

TEST(LowRankPacked, BrokenPackingIsRejected) {
  const std::vector<uint8_t> fast = encode(waving(9, 30), Profile::Fast);
  const Model m = read(fast);
  const uint64_t N = uint64_t(m.meta.frame_count) * m.low_rank.components;
  auto rejected = [&](const Packing& p) { return !opens(with_lrnk_payload(fast, packed_payload(m, p))); };
  ASSERT_FALSE(rejected({})) << "the unbent packing must open";
  EXPECT_TRUE(rejected({0, {}, 0, true})) << "Z beside R";
  EXPECT_TRUE(rejected({1, {}, 0, false})) << "raw_size above what the frame holds";
  EXPECT_TRUE(rejected({-1, {}, 0, false})) << "raw_size below what the frame holds";
  EXPECT_TRUE(rejected({0, {0}, 0, false})) << "a svarint left over";
  EXPECT_TRUE(rejected({0, {}, 1, false})) << "a truncated zstd frame";
  // A raw_size of 2^40 from a small frame: rejected by the counts, before any allocation.
  Packing huge;
  huge.raw_size_change = int64_t(1) << 40;
  EXPECT_TRUE(rejected(huge));
  EXPECT_LT(N, uint64_t(1) << 20);
}

// Packing is format 4's: a 3.x file whose LRNK is packed is rejected.
TEST(LowRankPacked, PackedDifferencesInAFormat3FileAreRejected) {
  const std::vector<uint8_t> small = encode(waving(9, 30), Profile::Small);
  ASSERT_EQ(small[4] | small[5] << 8, kFormatVersionMajor);
  const Model m = read(small);
  ASSERT_EQ(m.low_rank.components, 2u);
  EXPECT_FALSE(opens(with_lrnk_payload(small, packed_payload(m, {}))));
  const std::vector<uint8_t> plain = low_rank_bytes(m);
  EXPECT_TRUE(same_frames(small, with_lrnk_payload(small, plain)));
}

}  // namespace low_rank_packed
}  // namespace dcurve
