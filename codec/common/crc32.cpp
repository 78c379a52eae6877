#include "codec/common/crc32.h"

#include <array>
#include <cstring>

namespace dcurve {
namespace {
// zlib would bring a dependency the decoder does not otherwise need; a table CRC is a few
// lines. Sixteen tables (slicing-by-16) fold sixteen bytes per step: every residual stream
// checksums all its decoded values, where the CPU has no CRC instruction (WebAssembly) the
// decoder's largest per-frame cost after the low-rank sums.
constexpr size_t kSlices = 16;
using Tables = std::array<std::array<uint32_t, 256>, kSlices>;

Tables make_tables() {
  Tables t{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? (c >> 1) ^ 0x82F63B78u : c >> 1;
    t[0][i] = c;
  }
  // t[k][i]: the CRC of byte i followed by k zero bytes.
  for (size_t k = 1; k < kSlices; ++k)
    for (uint32_t i = 0; i < 256; ++i) t[k][i] = (t[k - 1][i] >> 8) ^ t[0][t[k - 1][i] & 0xff];
  return t;
}

uint32_t crc32c_tables(const uint8_t* p, size_t size, uint32_t c) {
  static const Tables t = make_tables();
  for (; size >= kSlices; size -= kSlices, p += kSlices) {
    // Bytes assembled explicitly: the same on any endianness and alignment.
    const uint32_t lo = c ^ (uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24);
    c = t[15][lo & 0xff] ^ t[14][(lo >> 8) & 0xff] ^ t[13][(lo >> 16) & 0xff] ^ t[12][lo >> 24];
    for (size_t k = 4; k < kSlices; ++k) c ^= t[kSlices - 1 - k][p[k]];
  }
  for (; size > 0; --size, ++p) c = t[0][(c ^ *p) & 0xff] ^ (c >> 8);
  return c;
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// SSE 4.2 has the CRC-32C step as an instruction: several times the tables' speed on the
// decoder's checksum of every decoded value.
__attribute__((target("sse4.2"))) uint32_t crc32c_instruction(const uint8_t* p, size_t size, uint32_t c) {
  uint64_t c64 = c;
  for (; size >= 8; size -= 8, p += 8) {
    uint64_t word;  // x86 is little-endian: the bytes in order
    std::memcpy(&word, p, 8);
    c64 = __builtin_ia32_crc32di(c64, word);
  }
  c = uint32_t(c64);
  for (; size > 0; --size, ++p) c = __builtin_ia32_crc32qi(c, *p);
  return c;
}
bool has_crc32c_instruction() {
  static const bool has = __builtin_cpu_supports("sse4.2");
  return has;
}
#else
uint32_t crc32c_instruction(const uint8_t* p, size_t size, uint32_t c) { return crc32c_tables(p, size, c); }
bool has_crc32c_instruction() { return false; }
#endif
}  // namespace

uint32_t crc32c_by_tables(const void* data, size_t size, uint32_t seed) {
  return ~crc32c_tables(static_cast<const uint8_t*>(data), size, ~seed);
}

uint32_t crc32c(const void* data, size_t size, uint32_t seed) {
  const uint8_t* p = static_cast<const uint8_t*>(data);
  return ~(has_crc32c_instruction() ? crc32c_instruction(p, size, ~seed) : crc32c_tables(p, size, ~seed));
}
}  // namespace dcurve
