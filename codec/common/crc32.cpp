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

const Tables& tables() {
  static const Tables t = make_tables();
  return t;
}

uint32_t crc32c_tables(const uint8_t* p, size_t size, uint32_t c) {
  const Tables& t = tables();
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
// Three lanes of kLaneBytes each are run side by side below: the instruction waits three
// cycles for its own result, so one lane leaves it idle two thirds of the time. The lanes'
// registers are joined by shifting the earlier ones over the bytes after them: running a
// register c over n zero bytes is linear in c over GF(2), so four tables of 256 give it.
constexpr size_t kLaneBytes = 2048;

struct ZeroShift {
  std::array<std::array<uint32_t, 256>, 4> t;
  uint32_t operator()(uint32_t c) const { return t[0][c & 0xff] ^ t[1][(c >> 8) & 0xff] ^ t[2][(c >> 16) & 0xff] ^ t[3][c >> 24]; }
};

// The register after `bytes` zero bytes, from each register value, by the one-table step.
ZeroShift make_zero_shift(size_t bytes) {
  const std::array<uint32_t, 256>& step = tables()[0];
  uint32_t basis[32];
  for (int i = 0; i < 32; ++i) {
    uint32_t c = uint32_t(1) << i;
    for (size_t k = 0; k < bytes; ++k) c = step[c & 0xff] ^ (c >> 8);
    basis[i] = c;
  }
  ZeroShift z{};
  for (int k = 0; k < 4; ++k)
    for (uint32_t b = 0; b < 256; ++b)
      for (int j = 0; j < 8; ++j)
        if (b >> j & 1) z.t[size_t(k)][b] ^= basis[8 * k + j];
  return z;
}

// SSE 4.2 has the CRC-32C step as an instruction: several times the tables' speed on the
// decoder's checksum of every decoded value.
__attribute__((target("sse4.2"))) uint32_t crc32c_instruction(const uint8_t* p, size_t size, uint32_t c) {
  if (size >= 3 * kLaneBytes) {
    static const ZeroShift over_one = make_zero_shift(kLaneBytes), over_two = make_zero_shift(2 * kLaneBytes);
    for (; size >= 3 * kLaneBytes; size -= 3 * kLaneBytes, p += 3 * kLaneBytes) {
      uint64_t a = c, b = 0, d = 0;
      for (size_t i = 0; i < kLaneBytes; i += 8) {
        uint64_t wa, wb, wd;  // x86 is little-endian: the bytes in order
        std::memcpy(&wa, p + i, 8);
        std::memcpy(&wb, p + kLaneBytes + i, 8);
        std::memcpy(&wd, p + 2 * kLaneBytes + i, 8);
        a = __builtin_ia32_crc32di(a, wa);
        b = __builtin_ia32_crc32di(b, wb);
        d = __builtin_ia32_crc32di(d, wd);
      }
      c = over_two(uint32_t(a)) ^ over_one(uint32_t(b)) ^ uint32_t(d);
    }
  }
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
