// The spatial weight tables of one encode, kept by content: every trial walk (grid trials,
// coding orders, cluster layouts, low-rank screening and trials) that meets a decoded
// geometry frame seen before reuses its tables instead of solving them again.
#pragma once
#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "codec/common/predictors.h"

namespace dcurve {

class SpatialWeightsStore : public SpatialWeightsSource {
 public:
  // byte_budget: tables and the geometry values they are keyed by, at most this many bytes
  // kept (least recently used dropped first; a table still in use by a walk lives on there).
  // Most tables an encode asks for are repeats; the default keeps nearly all that recur, a
  // much smaller budget solves many again, and a larger one saves few more solves.
  explicit SpatialWeightsStore(size_t byte_budget = size_t(32) << 20) : budget_(byte_budget) {}

  // spatial_weights(t, qg, mode), from the store when t's mesh (its fingerprint), the mode
  // and the V x 3 values qg match an entry. Thread-safe.
  std::shared_ptr<const std::vector<int32_t>> weights(const Traversal& t, const int32_t* qg, SpatialMode mode) override;

  // Tables computed and tables found, since construction.
  size_t computed() const;
  size_t reused() const;

 private:
  struct Entry {
    uint32_t fingerprint, hash;
    SpatialMode mode;
    std::vector<int32_t> geometry;  // the key's values
    std::shared_ptr<const std::vector<int32_t>> table;
    size_t bytes() const { return (geometry.size() + table->size()) * sizeof(int32_t); }
  };
  using Entries = std::list<Entry>;
  // The entry for the key, moved to the front (most recent); nullptr if none. Needs mutex_.
  const Entry* find(uint32_t fingerprint, uint32_t hash, SpatialMode mode, const int32_t* qg, size_t n);
  // Drops the least recently used entry and its index entry. Needs mutex_.
  void drop_oldest();

  const size_t budget_;
  mutable std::mutex mutex_;
  Entries entries_;  // most recently used first
  // The entries by (fingerprint, hash, mode): a lookup compares the values of the few entries
  // with that key rather than walking the list (thousands of entries for a small mesh).
  std::unordered_multimap<uint64_t, Entries::iterator> index_;
  size_t bytes_ = 0, computed_ = 0, reused_ = 0;
};

}  // namespace dcurve
