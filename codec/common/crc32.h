// CRC-32C (Castagnoli) of a byte range: the checksum of every .dcrv section.
#pragma once
#include <cstddef>
#include <cstdint>

namespace dcurve {
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
constexpr bool kVerifyChecksums = false;  // lets a fuzzer's mutations reach the parsers
#else
constexpr bool kVerifyChecksums = true;
#endif

uint32_t crc32c(const void* data, size_t size, uint32_t seed = 0);
// The same from tables alone, as a CPU without a CRC-32C instruction (WebAssembly) computes
// it: what a test compares on a machine that has one.
uint32_t crc32c_by_tables(const void* data, size_t size, uint32_t seed = 0);
}
