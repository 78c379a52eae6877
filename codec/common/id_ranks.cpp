#include "codec/common/id_ranks.h"

#include <algorithm>
#include <stdexcept>

namespace dcurve {
namespace {
// Set bits of x without a library call (x86-64's baseline has no popcnt instruction).
inline uint32_t popcount64(uint64_t x) {
  x -= (x >> 1) & 0x5555555555555555u;
  x = (x & 0x3333333333333333u) + ((x >> 2) & 0x3333333333333333u);
  x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fu;
  return uint32_t((x * 0x0101010101010101u) >> 56);
}
// The position of the k-th set bit of x (k >= 1, at most popcount64(x)).
inline uint32_t select64(uint64_t x, uint64_t k) {
  for (; k > 1; --k) x &= x - 1;
  return uint32_t(__builtin_ctzll(x));
}

// Bits lo..hi (inclusive, 0 <= lo <= hi <= 63) of a word.
inline uint64_t bit_range(uint32_t lo, uint32_t hi) {
  return (hi == 63 ? ~uint64_t(0) : (uint64_t(1) << (hi + 1)) - 1) & ~((uint64_t(1) << lo) - 1);
}
}  // namespace

IdRanks::IdRanks(uint32_t bound)
    : bound_(bound),
      bits_((size_t(bound) + 63) / 64, 0),
      word_before_(bits_.size(), 0),
      blocks_((bits_.size() >> kBlockWordsBits) + 2, 0) {}

bool IdRanks::contains(uint32_t id) const { return id < bound_ && (bits_[id / 64] >> (id % 64)) & 1; }

void IdRanks::insert(uint32_t id) {
  if (id >= bound_) throw std::out_of_range("IdRanks: id at or above the bound");
  if (contains(id)) return;
  const size_t word = id / 64, block = word >> kBlockWordsBits;
  bits_[word] |= uint64_t(1) << (id % 64);
  const size_t block_end = std::min(bits_.size(), (block + 1) << kBlockWordsBits);
  for (size_t w = word + 1; w < block_end; ++w) ++word_before_[w];
  for (size_t j = block + 1; j < blocks_.size(); j += j & (~j + 1)) ++blocks_[j];
  ++total_;
}

uint64_t IdRanks::block_below(size_t block) const {
  uint64_t s = 0;
  for (size_t j = block; j > 0; j -= j & (~j + 1)) s += blocks_[j];
  return s;
}

uint64_t IdRanks::count_below(uint64_t y) const {
  if (y >= bound_) return total_;
  const size_t word = size_t(y / 64);
  uint64_t n = block_below(word >> kBlockWordsBits) + word_before_[word];
  if (y % 64) n += popcount64(bits_[word] & ((uint64_t(1) << (y % 64)) - 1));
  return n;
}

uint64_t IdRanks::used_near(uint64_t lo, uint64_t hi) const {
  uint64_t n = 0;
  for (uint64_t w = lo / 64; w <= hi / 64; ++w) {
    const uint32_t from = w == lo / 64 ? uint32_t(lo % 64) : 0, to = w == hi / 64 ? uint32_t(hi % 64) : 63;
    n += popcount64(bits_[w] & bit_range(from, to));
  }
  return n;
}

uint64_t IdRanks::free_in(int64_t lo, int64_t hi) const {
  lo = std::max<int64_t>(lo, 0);
  if (lo > std::min(hi, kMaxVertexId)) return 0;
  if (uint64_t(hi) < bits_.size() * 64 && uint64_t(hi - lo) < kNearWords * 64)
    return uint64_t(hi - lo + 1) - used_near(uint64_t(lo), uint64_t(hi));
  return free_from(lo, count_below(uint64_t(lo)), hi);
}

uint64_t IdRanks::free_from(int64_t first, uint64_t used_before_first, int64_t last) const {
  last = std::min(last, kMaxVertexId);
  if (first > last) return 0;
  return uint64_t(last - first + 1) - (count_below(uint64_t(last) + 1) - used_before_first);
}

int64_t IdRanks::rank(int64_t from, uint32_t id) const {
  if (id == from) return 0;
  return id > from ? int64_t(free_in(from + 1, id)) : -int64_t(free_in(id, from - 1));
}

bool IdRanks::unrank_near(int64_t from, int64_t rank, uint32_t* id) const {
  const int64_t words = int64_t(bits_.size());
  const int64_t start = rank > 0 ? from + 1 : from - 1;  // the first id counted
  if (start < 0 || start >= words * 64) return false;
  uint64_t left = uint64_t(rank > 0 ? rank : -rank);
  int64_t w = start / 64;
  for (uint64_t step = 0; step < kNearWords && w >= 0 && w < words; ++step) {
    const uint32_t bit = uint32_t(start % 64);
    const uint64_t span = step > 0 ? ~uint64_t(0) : rank > 0 ? bit_range(bit, 63) : bit_range(0, bit);
    const uint64_t unused = ~bits_[size_t(w)] & span;
    const uint64_t n = popcount64(unused);
    if (n >= left) {
      // Counting down, the left-th unused id below is the (n - left + 1)-th from the bottom.
      const int64_t found = w * 64 + select64(unused, rank > 0 ? left : n - left + 1);
      if (found > kMaxVertexId) return false;
      *id = uint32_t(found);
      return true;
    }
    left -= n;
    w += rank > 0 ? 1 : -1;
  }
  return false;
}

bool IdRanks::unrank(int64_t from, int64_t rank, uint32_t* id) const {
  if (rank == 0) {
    if (from < 0 || from > kMaxVertexId) return false;
    *id = uint32_t(from);
    return true;
  }
  if (unrank_near(from, rank, id)) return true;
  // The answer lies within (used ids on that side) of from + rank: binary search there for
  // the id where the count of unused ids reaches |rank|, one end of the range fixed.
  const uint64_t total = count_below(uint64_t(1) << 32);
  if (rank > 0) {
    const int64_t first = std::max<int64_t>(from + 1, 0);
    if (first > kMaxVertexId) return false;
    const uint64_t used_before = count_below(uint64_t(first));
    int64_t lo = first + rank - 1, hi = std::min(kMaxVertexId, lo + int64_t(total - used_before));
    if (lo > kMaxVertexId || free_from(first, used_before, hi) < uint64_t(rank)) return false;
    while (lo < hi) {
      const int64_t mid = lo + (hi - lo) / 2;
      if (free_from(first, used_before, mid) >= uint64_t(rank)) hi = mid;
      else lo = mid + 1;
    }
    *id = uint32_t(lo);
    return true;
  }
  const int64_t last = std::min(from - 1, kMaxVertexId);
  if (last < 0) return false;
  const uint64_t used_through_last = count_below(uint64_t(last) + 1);
  auto free_down = [&](int64_t y) { return uint64_t(last - y + 1) - (used_through_last - count_below(uint64_t(y))); };
  int64_t hi = last + rank + 1, lo = std::max<int64_t>(0, hi - int64_t(used_through_last));
  if (hi < 0 || free_down(lo) < uint64_t(-rank)) return false;
  while (lo < hi) {
    const int64_t mid = lo + (hi - lo + 1) / 2;
    if (free_down(mid) >= uint64_t(-rank)) lo = mid;
    else hi = mid - 1;
  }
  *id = uint32_t(lo);
  return true;
}

}  // namespace dcurve
