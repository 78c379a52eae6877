// CRC-32C (Castagnoli) of a byte range: the checksum of every .dcrv section.
#pragma once
#include <cstddef>
#include <cstdint>

namespace dcurve {
uint32_t crc32c(const void* data, size_t size, uint32_t seed = 0);
}
