// A hash for integer keys read from files. std::hash of an integer is the integer itself, so
// hostile ids that are multiples of a table's bucket count would land in one bucket and make
// every lookup linear; mixing all bits first (the splitmix64 finalizer) spreads them.
#pragma once
#include <cstddef>
#include <cstdint>

namespace dcurve {

struct MixedHash {
  size_t operator()(uint64_t k) const {
    k ^= k >> 30;
    k *= 0xbf58476d1ce4e5b9ull;
    k ^= k >> 27;
    k *= 0x94d049bb133111ebull;
    k ^= k >> 31;
    return size_t(k);
  }
};

}  // namespace dcurve
