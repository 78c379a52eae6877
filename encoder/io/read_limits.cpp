#include "encoder/io/read_limits.h"

#include <unistd.h>

#include <algorithm>

#include "codec/common/error.h"

namespace dcurve {

uint64_t default_max_memory() {
  constexpr uint64_t kCap = uint64_t(4) << 30;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return kCap;
  return std::min(kCap, uint64_t(pages) * uint64_t(page) / 2);
}

bool MemoryBudget::take(uint64_t count, uint64_t element_bytes, const std::string& what, std::string* error) {
  if (!fits(count, element_bytes))
    return fail(error, what + " needs " + std::to_string(count) + " x " + std::to_string(element_bytes) +
                           " bytes, more than the memory limit of " + std::to_string(max_) +
                           " bytes allows (--max-memory)");
  left_ -= count * element_bytes;
  return true;
}

}  // namespace dcurve
