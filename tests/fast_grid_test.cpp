// The fast profile's search (encoder/rate/fast_grid.h, fast_low_rank.h): the grid and the
// low-rank count it keeps code no larger than the alternatives it is meant to rank.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "encoder/encoder.h"
#include "test_util.h"

namespace dcurve {
namespace {
namespace fast_grid_test {

// A weight in [-1, 1] with no pattern in time: a hash of (mode, frame).
float weight(uint32_t k, uint32_t f) {
  uint32_t h = k * 0x9e3779b9u ^ (f + 1) * 0x85ebca6bu;
  h ^= h >> 15;
  h *= 0xc2b2ae35u;
  h ^= h >> 13;
  return float(h % 2001) / 1000.0f - 1.0f;
}

// A sheet moved by `modes` rough shapes, each with weights that follow no pattern in time:
// a few components explain little of it, all of them explain it all.
Animation many_modes(uint32_t W, uint32_t frames, int modes) {
  Animation a;
  a.vertex_count = W * W;
  a.faces = test::grid_faces(W, W);
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t v = 0; v < a.vertex_count; ++v) {
      const float x = float(v % W) / float(W), y = float(v / W) / float(W);
      float z = 0;
      for (int k = 1; k <= modes; ++k)
        z += 0.004f * weight(uint32_t(k) + 1000, v) * weight(uint32_t(k), f);
      xyz.insert(xyz.end(), {x, y, z});
    }
    a.frames.push_back(xyz);
  }
  return a;
}

size_t fast_bytes(const Animation& a, double grid, int low_rank) {
  EncodeOptions o;
  o.profile = Profile::Fast;
  o.grid_refinement = grid;
  o.low_rank = low_rank;
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(a, o, &bytes, nullptr, &err)) << err;
  return bytes.size();
}

// Counts forced one by one code no smaller than the searched count: not the ones it tried
// first, nor the most the 30 frames have (32 asks for all 29), which no ladder step names.
TEST(FastGrid, TheSearchedCountIsNoLargerThanAnyForcedOne) {
  const Animation a = many_modes(24, 30, 20);
  const size_t searched = fast_bytes(a, 4, -1);
  for (int K : {0, 2, 8, 16, 24, 32}) EXPECT_LE(searched, fast_bytes(a, 4, K)) << K;
}

// With the grid left to the encoder, the file is no larger than either grid its default
// search brackets, each with its own count searched.
TEST(FastGrid, TheChosenGridIsNoLargerThanEitherBracketedOne) {
  const Animation a = many_modes(12, 30, 6);
  const size_t chosen = fast_bytes(a, 0, -1);
  for (double grid : {3.0, 8.0}) EXPECT_LE(chosen, fast_bytes(a, grid, -1)) << grid;
}

}  // namespace fast_grid_test
}  // namespace
}  // namespace dcurve
