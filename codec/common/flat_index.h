// An open-addressing hash table from 64-bit keys to 32-bit values, for the per-vertex and
// per-edge state of the FACE Compact walk, which looks up a key several times per triangle:
// one flat array probed linearly instead of a node per key (std::unordered_map), several
// times faster on a mesh's worth of lookups. Keys are mixed (MixedHash) so hostile ids do not
// pile into one run of slots.
#pragma once
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "codec/common/mixed_hash.h"

namespace dcurve {

class FlatIndex {
 public:
  static constexpr uint32_t kMissing = UINT32_MAX;
  // UINT64_MAX marks an empty slot: no key may equal it (vertex ids and edge keys of ids up
  // to 2^32 - 2 never do).
  static constexpr uint64_t kEmpty = UINT64_MAX;

  // The value stored for key, or kMissing.
  uint32_t find(uint64_t key) const {
    if (keys_.empty()) return kMissing;
    for (size_t i = MixedHash()(key) & mask_;; i = (i + 1) & mask_) {
      if (keys_[i] == key) return values_[i];
      if (keys_[i] == kEmpty) return kMissing;
    }
  }
  bool contains(uint64_t key) const { return find(key) != kMissing; }
  // Stores key -> value unless key is present; true when it was inserted.
  bool insert(uint64_t key, uint32_t value) {
    if (key == kEmpty) throw std::invalid_argument("FlatIndex: reserved key");
    if ((size_ + 1) * 2 > keys_.size()) grow();
    for (size_t i = MixedHash()(key) & mask_;; i = (i + 1) & mask_) {
      if (keys_[i] == key) return false;
      if (keys_[i] == kEmpty) {
        keys_[i] = key;
        values_[i] = value;
        ++size_;
        return true;
      }
    }
  }
  // Room for n keys without growing.
  void reserve(size_t n) {
    size_t slots = keys_.empty() ? 16 : keys_.size();
    while (slots < 2 * n + 2) slots *= 2;
    if (slots > keys_.size()) rehash(slots);
  }
  size_t size() const { return size_; }
  size_t bytes() const { return keys_.capacity() * 8 + values_.capacity() * 4; }

 private:
  // Twice the slots (at least 16), every key placed again.
  void grow() { rehash(keys_.empty() ? 16 : 2 * keys_.size()); }
  // `slots` (a power of two) slots, every key placed again.
  void rehash(size_t slots) {
    std::vector<uint64_t> keys(slots, kEmpty);
    std::vector<uint32_t> values(keys.size());
    keys.swap(keys_);
    values.swap(values_);
    mask_ = keys_.size() - 1;
    size_ = 0;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) insert(keys[i], values[i]);
  }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t mask_ = 0, size_ = 0;
};

}  // namespace dcurve
