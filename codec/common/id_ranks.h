// A growing set of vertex ids (each in [0, 2^32 - 2]) that answers "how many ids below y"
// in a few dozen steps whatever the ids, so the FACE Compact coder can code a new vertex's
// id by its rank among the ids NOT yet used: on a mesh whose ids follow its surface, most
// ids near a gate are already used, and skipping them makes the coded numbers much smaller.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/flat_index.h"

namespace dcurve {

// The largest vertex id a file may hold: ids lie in [0, 2^32 - 2].
constexpr int64_t kMaxVertexId = int64_t(UINT32_MAX) - 1;

class IdRanks {
 public:
  IdRanks();
  bool contains(uint32_t id) const;
  void insert(uint32_t id);  // no effect when already present
  // Ids in the set that are < y, for y in [0, 2^32].
  uint64_t count_below(uint64_t y) const;
  // Ids in [0, 2^32 - 2] NOT in the set, inside the inclusive range [lo, hi] (clipped).
  uint64_t free_in(int64_t lo, int64_t hi) const;
  // The signed rank of `id` (not in the set) seen from `from` (any value): 0 when equal,
  // else +-(free ids between them, counting id but not from).
  int64_t rank(int64_t from, uint32_t id) const;
  // Reverses rank: false when no free id in [0, 2^32 - 2] has that rank.
  bool unrank(int64_t from, int64_t rank, uint32_t* id) const;

 private:
  static constexpr int kTopBits = 12, kMidBits = 10, kLowBits = 10;
  struct Fenwick {
    std::vector<uint32_t> sum;
    explicit Fenwick(size_t n) : sum(n + 1, 0) {}
    void add(size_t i);                // one more at index i
    uint64_t below(size_t i) const;    // total at indices < i
  };
  Fenwick top_;                                   // per top bucket
  // Per used top bucket (found through mid_of_): per mid bucket.
  FlatIndex mid_of_;
  std::vector<Fenwick> mids_;
  // Per used (top, mid): the ids' bits, 64 per word, and per word the ids in earlier words.
  struct Low {
    uint64_t bits[(1u << kLowBits) / 64] = {};
    uint16_t before[(1u << kLowBits) / 64] = {};
  };
  FlatIndex low_of_;  // (top, mid) -> its Low
  std::vector<Low> lows_;
  // Ids in [0, y) given count_below(first) for some first <= y: the binary searches of
  // unrank keep one end fixed.
  uint64_t free_from(int64_t first, uint64_t used_before_first, int64_t last) const;
};

}  // namespace dcurve
