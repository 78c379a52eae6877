// Compressing one zstd frame (codec/decompress/zstd_frame.h reads it back).
#pragma once
#include <cstdint>
#include <vector>

namespace dcurve {

// raw as one zstd frame at `level` (1..22); empty only if zstd fails, which a buffer of
// ZSTD_compressBound bytes rules out.
std::vector<uint8_t> zstd_frame(const std::vector<uint8_t>& raw, int level);

}  // namespace dcurve
