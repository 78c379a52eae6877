#include "codec/common/id_ranks.h"

#include <algorithm>
#include <bitset>

namespace dcurve {

void IdRanks::Fenwick::add(size_t i) {
  for (size_t j = i + 1; j < sum.size(); j += j & (~j + 1)) ++sum[j];
}

uint64_t IdRanks::Fenwick::below(size_t i) const {
  uint64_t s = 0;
  for (size_t j = i; j > 0; j -= j & (~j + 1)) s += sum[j];
  return s;
}

IdRanks::IdRanks() : top_(size_t(1) << kTopBits) {}

bool IdRanks::contains(uint32_t id) const {
  const uint32_t at = low_of_.find(id >> kLowBits);
  if (at == FlatIndex::kMissing) return false;
  const uint32_t low = id & ((1u << kLowBits) - 1);
  return (lows_[at].bits[low / 64] >> (low % 64)) & 1;
}

void IdRanks::insert(uint32_t id) {
  if (contains(id)) return;
  const uint32_t top = id >> (kMidBits + kLowBits), mid = (id >> kLowBits) & ((1u << kMidBits) - 1);
  const uint32_t low = id & ((1u << kLowBits) - 1);
  top_.add(top);
  if (mid_of_.insert(top, uint32_t(mids_.size()))) mids_.emplace_back(size_t(1) << kMidBits);
  mids_[mid_of_.find(top)].add(mid);
  if (low_of_.insert(id >> kLowBits, uint32_t(lows_.size()))) lows_.emplace_back();
  Low& l = lows_[low_of_.find(id >> kLowBits)];
  l.bits[low / 64] |= uint64_t(1) << (low % 64);
  for (uint32_t w = low / 64 + 1; w < (1u << kLowBits) / 64; ++w) ++l.before[w];
}

uint64_t IdRanks::count_below(uint64_t y) const {
  if (y >> 32) return top_.below(top_.sum.size() - 1);
  const uint32_t top = uint32_t(y >> (kMidBits + kLowBits)), mid = uint32_t(y >> kLowBits) & ((1u << kMidBits) - 1);
  const uint32_t low = uint32_t(y) & ((1u << kLowBits) - 1);
  uint64_t n = top_.below(top);
  const uint32_t m = mid_of_.find(top);
  if (m != FlatIndex::kMissing) n += mids_[m].below(mid);
  const uint32_t l = low_of_.find(uint32_t(y >> kLowBits));
  if (l != FlatIndex::kMissing) {
    n += lows_[l].before[low / 64];
    if (low % 64) n += std::bitset<64>(lows_[l].bits[low / 64] & ((uint64_t(1) << (low % 64)) - 1)).count();
  }
  return n;
}

uint64_t IdRanks::free_in(int64_t lo, int64_t hi) const {
  lo = std::max<int64_t>(lo, 0);
  if (lo > std::min(hi, kMaxVertexId)) return 0;
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

bool IdRanks::unrank(int64_t from, int64_t rank, uint32_t* id) const {
  if (rank == 0) {
    if (from < 0 || from > kMaxVertexId) return false;
    *id = uint32_t(from);
    return true;
  }
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
