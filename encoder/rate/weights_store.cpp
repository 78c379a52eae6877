#include "encoder/rate/weights_store.h"

#include <algorithm>
#include <iterator>

#include "codec/common/crc32.h"

namespace dcurve {

namespace {
uint64_t index_key(uint32_t fingerprint, uint32_t hash, SpatialMode mode) {
  return (uint64_t(fingerprint) << 32 | hash) ^ (uint64_t(mode) << 56);
}
}  // namespace

const SpatialWeightsStore::Entry* SpatialWeightsStore::find(uint32_t fingerprint, uint32_t hash, SpatialMode mode,
                                                            const int32_t* qg, size_t n) {
  const auto range = index_.equal_range(index_key(fingerprint, hash, mode));
  for (auto i = range.first; i != range.second; ++i) {
    const Entries::iterator it = i->second;
    if (it->fingerprint != fingerprint || it->hash != hash || it->mode != mode || it->geometry.size() != n ||
        !std::equal(it->geometry.begin(), it->geometry.end(), qg))
      continue;
    entries_.splice(entries_.begin(), entries_, it);  // the index's iterator stays valid
    return &entries_.front();
  }
  return nullptr;
}

void SpatialWeightsStore::drop_oldest() {
  const Entries::iterator oldest = std::prev(entries_.end());
  const auto range = index_.equal_range(index_key(oldest->fingerprint, oldest->hash, oldest->mode));
  for (auto i = range.first; i != range.second; ++i)
    if (i->second == oldest) {
      index_.erase(i);
      break;
    }
  bytes_ -= oldest->bytes();
  entries_.erase(oldest);
}

std::shared_ptr<const std::vector<int32_t>> SpatialWeightsStore::weights(const Traversal& t, const int32_t* qg,
                                                                         SpatialMode mode) {
  const size_t n = t.order.size() * 3;
  if (t.fingerprint == 0) return std::make_shared<const std::vector<int32_t>>(spatial_weights(t, qg, mode));
  const uint32_t hash = crc32c(qg, n * sizeof(int32_t));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (const Entry* e = find(t.fingerprint, hash, mode, qg, n)) {
      ++reused_;
      return e->table;
    }
  }
  // Solved outside the lock, so other threads' walks go on meanwhile; two threads may solve
  // the same table at once, and the second keeps the first's entry.
  auto table = std::make_shared<const std::vector<int32_t>>(spatial_weights(t, qg, mode));
  std::lock_guard<std::mutex> lock(mutex_);
  ++computed_;
  if (const Entry* e = find(t.fingerprint, hash, mode, qg, n)) return e->table;
  entries_.push_front({t.fingerprint, hash, mode, std::vector<int32_t>(qg, qg + n), table});
  index_.emplace(index_key(t.fingerprint, hash, mode), entries_.begin());
  bytes_ += entries_.front().bytes();
  while (bytes_ > budget_ && entries_.size() > 1) drop_oldest();
  return table;
}

size_t SpatialWeightsStore::computed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return computed_;
}

size_t SpatialWeightsStore::reused() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return reused_;
}

}  // namespace dcurve
