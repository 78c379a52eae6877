#include "codec/compress/zstd_frame_writer.h"

#include <zstd.h>

namespace dcurve {

std::vector<uint8_t> zstd_frame(const std::vector<uint8_t>& raw, int level) {
  std::vector<uint8_t> packed(ZSTD_compressBound(raw.size()));
  const size_t n = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), level);
  packed.resize(ZSTD_isError(n) ? 0 : n);
  return packed;
}

}  // namespace dcurve
