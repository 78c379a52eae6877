// What a reader may spend on one input: memory, checked against what the file declares before
// anything is allocated, and the folders a glTF may read its buffers from.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Half the physical memory, at most 4 GiB.
uint64_t default_max_memory();

struct ReadLimits {
  uint64_t max_memory = default_max_memory();
  // Folders besides the glTF's own whose files its buffer uris may name
  // (--allow-resources-outside).
  std::vector<std::string> resource_dirs;
};

// Bytes a reader has left: each array sized from a file's counts is taken from it first, so a
// few bytes declaring billions of elements are an error, not an allocation.
class MemoryBudget {
 public:
  explicit MemoryBudget(uint64_t max_bytes) : left_(max_bytes), max_(max_bytes) {}
  // Takes count x element_bytes (no overflow); false, with an error naming `what`, when that is
  // more than is left.
  bool take(uint64_t count, uint64_t element_bytes, const std::string& what, std::string* error);
  // Whether count x element_bytes would fit, without taking it.
  bool fits(uint64_t count, uint64_t element_bytes) const { return element_bytes == 0 || count <= left_ / element_bytes; }

 private:
  uint64_t left_, max_;
};

}  // namespace dcurve
