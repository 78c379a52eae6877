// One zstd frame whose decompressed size the file declares: the container's sections, the
// fast payload's streams and LRNK's packed differences all store data this way.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dcurve {

// Whether a frame of `stored` bytes may claim `raw` decompressed bytes: at most 4096 times
// its size, with a floor of 1 MiB (format_spec/dcrv.md section 15), so that a small hostile
// file cannot ask for unbounded memory. Checked before anything is allocated.
inline bool zstd_size_plausible(uint64_t raw, uint64_t stored) {
  constexpr uint64_t kMaxExpansion = 4096, kFloor = uint64_t(1) << 20;
  return raw <= (stored * kMaxExpansion > kFloor ? stored * kMaxExpansion : kFloor);
}

// Decompresses the frame p[0, stored) into *out (resized to raw): false unless it is one
// valid frame of exactly raw bytes. ZSTD_decompress alone: the WebAssembly build's zstd
// (web/zstd_shim) offers nothing else.
bool decompress_exactly(const uint8_t* p, size_t stored, uint64_t raw, std::vector<uint8_t>* out);

}  // namespace dcurve
