// A growing set of vertex ids below a bound (the file's vertex count) that answers "how many
// ids below y" in a few steps, so the FACE Compact coder can code a new vertex's id by its
// rank among the ids NOT yet used in [0, 2^32 - 2]: on a mesh whose ids follow its surface,
// most ids near a gate are already used, and skipping them makes the coded numbers much
// smaller. Ids at or above the bound are never inserted, so they all count as unused.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dcurve {

// The largest vertex id a file may hold: ids lie in [0, 2^32 - 2].
constexpr int64_t kMaxVertexId = int64_t(UINT32_MAX) - 1;

class IdRanks {
 public:
  // Room for ids in [0, bound): bound / 8 bytes of bits and a few percent more.
  explicit IdRanks(uint32_t bound);
  uint32_t bound() const { return bound_; }
  bool contains(uint32_t id) const;  // false at or above the bound
  void insert(uint32_t id);          // id < bound(); no effect when already present
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
  // Blocks of 64 words (4096 ids): a Fenwick tree counts the ids of earlier blocks, and per
  // word the ids of the block's earlier words, so a count is a few steps and a popcount.
  static constexpr int kBlockWordsBits = 6;
  uint64_t block_below(size_t block) const;
  // Ids in the set in [lo, hi], both inside the words, hi - lo < kNearWords * 64: a few
  // popcounts (most ranks the coder asks for are between ids a few apart).
  uint64_t used_near(uint64_t lo, uint64_t hi) const;
  // unrank by a walk over at most kNearWords words from `from`: false when it would leave the
  // words or take longer (the binary search then answers).
  bool unrank_near(int64_t from, int64_t rank, uint32_t* id) const;
  static constexpr uint64_t kNearWords = 4;
  // Ids in [0, y) given count_below(first) for some first <= y: the binary searches of
  // unrank keep one end fixed.
  uint64_t free_from(int64_t first, uint64_t used_before_first, int64_t last) const;
  uint32_t bound_;
  uint64_t total_ = 0;
  std::vector<uint64_t> bits_;
  std::vector<uint16_t> word_before_;  // ids in the block's words before this one
  std::vector<uint32_t> blocks_;       // Fenwick tree over the blocks (1-based)
};

}  // namespace dcurve
