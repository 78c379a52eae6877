#include "codec/decompress/zstd_frame.h"

#include <zstd.h>

namespace dcurve {

bool decompress_exactly(const uint8_t* p, size_t stored, uint64_t raw, std::vector<uint8_t>* out) {
  if (raw > SIZE_MAX) return false;
  out->resize(size_t(raw));
  const size_t n = ZSTD_decompress(out->data(), out->size(), p, stored);
  return !ZSTD_isError(n) && n == raw;
}

}  // namespace dcurve
