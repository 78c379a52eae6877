// Fit over the fast traversal (format 4.3, format_spec/residual.md section 10.7): its sets
// reach only earlier positions, a smooth basis vector over a curved mean codes smaller with
// Fit than with parallelograms and round-trips exactly, and the flag is refused wherever the
// format forbids it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "codec/common/fast_fit.h"
#include "codec/common/fast_residual.h"
#include "codec/common/fast_traversal.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/decompress/fast_residual_decoder.h"
#include "test_util.h"

namespace dcurve {
namespace fast_fit_test {

constexpr uint32_t kW = 12, kH = 11, kV = kW * kH;
constexpr size_t kN = size_t(kV) * 3;
constexpr uint8_t kS = fast_residual::kSpatialFlag, kFit = fast_residual::kFitFlag | kS;

// Two pseudo-frames of a basis payload: a curved sheet as the mean (grid units), then a
// smooth field over it, as a low-rank basis vector is.
std::vector<int32_t> mean_and_vector() {
  std::vector<int32_t> q(2 * kN);
  for (uint32_t v = 0; v < kV; ++v) {
    const double x = 40.0 * (v % kW), y = 40.0 * (v / kW), z = (x * x - 0.5 * y * y) / 300.0;
    const double p[3] = {x, y, z};
    for (int a = 0; a < 3; ++a) {
      q[size_t(v) * 3 + size_t(a)] = int32_t(std::lround(p[a]));
      q[kN + size_t(v) * 3 + size_t(a)] = int32_t(std::lround(60 * std::sin(x / 90 + a) * std::cos(y / 120)));
    }
  }
  return q;
}

std::vector<uint8_t> basis_chunk(const FastTraversal& t, const std::vector<uint32_t>& faces,
                                 const std::vector<int32_t>& q, uint8_t vector_kind) {
  const FastFit fit = fast_fit(faces, t, q.data());
  const uint8_t kinds[2] = {kS, vector_kind};
  return encode_fast_chunk(t, kV, kinds, 2, q.data(), nullptr, &fit);
}

TEST(FastFit, SetsHoldOnlyEarlierPositionsNeighboursFirst) {
  const std::vector<uint32_t> faces = test::grid_faces(kW, kH);
  const FastTraversal t = fast_traversal(faces, kV);
  const FastFit fit = fast_fit(faces, t, mean_and_vector().data());
  ASSERT_EQ(fit.offsets.size(), size_t(kV) + 1);
  size_t full = 0;
  for (uint32_t i = 0; i < kV; ++i) {
    const uint32_t begin = fit.offsets[i], end = fit.offsets[i + 1];
    EXPECT_LE(end - begin, kMaxFitPoints);
    for (uint32_t k = begin; k < end; ++k) EXPECT_LT(fit.refs[k], i) << "position " << i;
    if (end > begin) {
      EXPECT_EQ(fit.weights[begin], 0);
    }
    full += end - begin >= 6;
  }
  EXPECT_GT(full, size_t(kV) / 2);  // inside the sheet: two rings of earlier vertices
  const FastTraversal chain = fast_traversal({}, kV);
  const FastFit none = fast_fit({}, chain, mean_and_vector().data());
  EXPECT_TRUE(none.refs.empty());  // no triangles: every set empty, every prediction 0
}

TEST(FastFit, ASmoothBasisVectorCodesSmallerWithFitAndRoundTrips) {
  const std::vector<uint32_t> faces = test::grid_faces(kW, kH);
  const FastTraversal t = fast_traversal(faces, kV);
  const std::vector<int32_t> q = mean_and_vector();
  const std::vector<uint8_t> with_fit = basis_chunk(t, faces, q, kFit);
  const std::vector<uint8_t> parallelograms = basis_chunk(t, faces, q, kS);
  ASSERT_FALSE(with_fit.empty());
  ASSERT_FALSE(parallelograms.empty());
  EXPECT_LT(with_fit.size(), parallelograms.size());
  std::vector<int32_t> out(q.size(), 7);
  std::string err;
  ASSERT_TRUE(decode_fast_chunk(t, kV, with_fit.data(), with_fit.size(), 2, nullptr, out.data(), &err, &faces)) << err;
  EXPECT_EQ(out, q);
  // Over other triangles (the first cells' missing) the sets differ, so the same bytes decode
  // to other values: the frame checksum refuses them.
  const std::vector<uint32_t> other(faces.begin() + 12, faces.end());
  EXPECT_FALSE(decode_fast_chunk(t, kV, with_fit.data(), with_fit.size(), 2, nullptr, out.data(), &err, &other));
}

// Rough vectors: residuals past a value byte's range take escapes of several bytes, and
// the side-by-side decoding must still find where each vector's values start.
TEST(FastFit, RoughVectorsWithEscapedValuesDecodeSideBySide) {
  const std::vector<uint32_t> faces = test::grid_faces(kW, kH);
  const FastTraversal t = fast_traversal(faces, kV);
  std::vector<int32_t> q = mean_and_vector();
  q.resize(4 * kN);
  std::mt19937 rng(11);
  for (size_t i = kN; i < q.size(); ++i)
    q[i] = rng() % 4 == 0 ? int32_t(rng() % 400001) - 200000 : int32_t(rng() % 7) - 3;
  const FastFit fit = fast_fit(faces, t, q.data());
  const uint8_t kinds[4] = {kS, kFit, kFit, kFit};
  const std::vector<uint8_t> bytes = encode_fast_chunk(t, kV, kinds, 4, q.data(), nullptr, &fit);
  ASSERT_FALSE(bytes.empty());
  std::vector<int32_t> out(q.size(), 7);
  std::string err;
  ASSERT_TRUE(decode_fast_chunk(t, kV, bytes.data(), bytes.size(), 4, nullptr, out.data(), &err, &faces)) << err;
  EXPECT_EQ(out, q);
}

TEST(FastFit, TheFlagIsRefusedWhereTheFormatForbidsIt) {
  const std::vector<uint32_t> faces = test::grid_faces(kW, kH);
  const FastTraversal t = fast_traversal(faces, kV);
  const std::vector<int32_t> q = mean_and_vector();
  const FastFit fit = fast_fit(faces, t, q.data());
  auto coded = [&](uint8_t first, uint8_t second) {
    const uint8_t kinds[2] = {first, second};
    return encode_fast_chunk(t, kV, kinds, 2, q.data(), nullptr, &fit);
  };
  EXPECT_TRUE(coded(kFit, kS).empty());                                     // frame 0 is the shape itself
  EXPECT_TRUE(coded(kS, kFit | fast_residual::kSmoothFlag).empty());        // smooth and Fit at once
  EXPECT_TRUE(coded(kS, fast_residual::kFitFlag).empty());                  // Fit without the spatial flag
  const std::vector<uint8_t> good = coded(kS, kFit);
  ASSERT_FALSE(good.empty());
  std::vector<int32_t> out(q.size());
  std::string err;
  // Outside a basis payload (RESI) the same chunk is refused.
  EXPECT_FALSE(decode_fast_chunk(t, kV, good.data(), good.size(), 2, nullptr, out.data(), &err));
  EXPECT_NE(err.find("predictor"), std::string::npos) << err;
  FastChunkDecoder runtime;
  EXPECT_FALSE(runtime.open(good.data(), good.size(), kV, 2, false, &t, &err));
  // Frame 0 with the Fit flag, written by hand (the encoder refuses it): refused on reading.
  std::vector<uint8_t> bad = good;
  bad[0] = kFit;
  EXPECT_FALSE(decode_fast_chunk(t, kV, bad.data(), bad.size(), 2, nullptr, out.data(), &err, &faces));
}

}  // namespace fast_fit_test
}  // namespace dcurve
