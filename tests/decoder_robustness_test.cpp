// The runtime decoder on hostile input: every truncation and single-byte flip of a small
// encoded file, random bytes, and files with valid checksums but absurd content. Each must
// fail with a message, never crash (the sanitizer build checks reads and allocations).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codec/compress/container_writer.h"
#include "container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "test_models.h"
#include "test_util.h"

namespace dcurve {
namespace {

std::vector<uint8_t> small_encoded_file() {
  Animation anim;
  anim.vertex_count = 12;
  for (uint32_t v = 0; v + 2 < 12; ++v) anim.faces.insert(anim.faces.end(), {v, v + 1, v + 2});
  for (int f = 0; f < 4; ++f) {
    std::vector<float> fr(36);
    for (int i = 0; i < 36; ++i) fr[i] = float(i % 5) * 0.2f + 0.03f * f * float(i % 3);
    anim.frames.push_back(fr);
  }
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(anim, EncodeOptions{}, &bytes, nullptr, &err)) << err;
  return bytes;
}

bool opens(const std::vector<uint8_t>& bytes, std::string* err) { return test::opens_and_decodes(bytes, err); }

TEST(DecoderRobustness, RejectsEveryTruncation) {
  const std::vector<uint8_t> bytes = small_encoded_file();
  std::string err;
  ASSERT_TRUE(opens(bytes, &err)) << err;
  for (size_t n = 0; n < bytes.size(); ++n) {
    err.clear();
    EXPECT_FALSE(opens(std::vector<uint8_t>(bytes.begin(), bytes.begin() + n), &err)) << n;
    EXPECT_FALSE(err.empty()) << n;
  }
}

TEST(DecoderRobustness, DetectsEverySingleByteFlip) {
  const std::vector<uint8_t> bytes = small_encoded_file();
  for (size_t i = 0; i < bytes.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> bad = bytes;
      bad[i] ^= uint8_t(1 << bit);
      std::string err;
      EXPECT_FALSE(opens(bad, &err)) << "byte " << i << " bit " << bit;
    }
}

TEST(DecoderRobustness, RejectsRandomBytes) {
  std::mt19937 rng(3);
  const std::vector<uint8_t> good = small_encoded_file();
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> bytes(rng() % 400);
    for (auto& b : bytes) b = uint8_t(rng());
    if (i % 2 && bytes.size() >= 20) std::copy(good.begin(), good.begin() + 20, bytes.begin());
    std::string err;
    EXPECT_FALSE(opens(bytes, &err));
    EXPECT_FALSE(err.empty());
  }
  std::string err;
  EXPECT_FALSE(Decoder::open_memory(nullptr, 10, &err));
  EXPECT_FALSE(Decoder::open_memory(nullptr, 0, &err));
}

// Valid checksums, plausible sizes, wrong meaning: each needs the semantic checks.
TEST(DecoderRobustness, RejectsInconsistentModels) {
  auto expect_reject = [](Model m, const char* why) {
    std::vector<uint8_t> bytes = write_container(m);
    std::string err;
    EXPECT_FALSE(Decoder::open_memory(bytes.data(), bytes.size(), &err)) << why;
    EXPECT_FALSE(err.empty()) << why;
  };
  using testing::small_model;
  Model m = small_model(4);
  m.faces[5] = 6;
  expect_reject(m, "face index out of range");
  m = small_model(4);
  m.curves.vertices[1] = 4;
  expect_reject(m, "vertex on two curves");
  m = small_model(4);
  m.curves.u[2] = 0.25f;
  expect_reject(m, "u decreasing");
  m = small_model(4, {0, 2, 3});
  m.segments[1].first_frame = 1;
  expect_reject(m, "segments overlap");
  m = small_model(4, {0, 2});
  expect_reject(m, "segments stop short of the last frame");
  m = small_model(4);
  m.meta.frame_count = 5;
  expect_reject(m, "residual stream shorter than the frame count");
  m = small_model(4);
  m.meta.vertex_count = 7;
  expect_reject(m, "curves do not cover the vertex count");
  m = small_model(4);
  m.meta.tolerance = -1;
  expect_reject(m, "negative tolerance");
  m = small_model(4);
  m.residual.step = std::nan("");
  expect_reject(m, "NaN grid step");
}

TEST(DecoderRobustness, OpenFileNamesThePath) {
  std::string err;
  EXPECT_FALSE(Decoder::open_file("/nonexistent/dir/a.dcrv", &err));
  EXPECT_NE(err.find("/nonexistent/dir/a.dcrv"), std::string::npos) << err;
}

}  // namespace
}  // namespace dcurve
