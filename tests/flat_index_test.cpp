// FlatIndex (codec/common/flat_index.h), the FACE Compact walk's vertex and edge tables:
// it answers as a map does through every growth, including for keys built to collide.
#include <gtest/gtest.h>

#include <random>
#include <unordered_map>

#include "codec/common/flat_index.h"

namespace dcurve {
namespace flat_index_test {

TEST(FlatIndex, AnswersAsAMapThroughEveryGrowth) {
  FlatIndex index;
  std::unordered_map<uint64_t, uint32_t> reference;
  std::mt19937_64 rng(3);
  for (uint32_t i = 0; i < 50000; ++i) {
    // Edge keys of nearby ids, vertex ids spread over 32 bits, and repeats.
    const uint64_t key = i % 3 == 0 ? (uint64_t(rng() % 200) << 32 | rng() % 200)
                         : i % 3 == 1 ? rng() % 0xfffffffeull
                                      : uint64_t(i / 2) << 20;
    const bool fresh = reference.emplace(key, i).second;
    EXPECT_EQ(index.insert(key, i), fresh);
  }
  EXPECT_EQ(index.size(), reference.size());
  for (const auto& [key, value] : reference) ASSERT_EQ(index.find(key), value);
  for (uint32_t i = 0; i < 1000; ++i) {
    const uint64_t absent = (uint64_t(0xfffffffe) << 32) | i;  // no key above uses this high word
    EXPECT_FALSE(index.contains(absent));
  }
  EXPECT_FALSE(FlatIndex().contains(7));
}

}  // namespace flat_index_test
}  // namespace dcurve
