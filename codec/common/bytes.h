// Little-endian byte writing and bounds-checked reading. Every read either succeeds or
// sets `ok = false` and returns zero, so parsers check once at the end of a record.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace dcurve {

// Signed <-> unsigned for varints: 0, -1, 1, -2 ... -> 0, 1, 2, 3 ... (no shift of a
// negative value, which C++17 leaves undefined).
inline uint64_t zigzag_encode(int64_t v) { return (uint64_t(v) << 1) ^ (v < 0 ? ~uint64_t(0) : 0); }
inline int64_t zigzag_decode(uint64_t z) { return int64_t(z >> 1) ^ -int64_t(z & 1); }

// base + the zigzag-coded delta, for ids (base within [0, 2^32]). False, instead of signed
// overflow, when a hostile delta is beyond any id range.
inline bool add_zigzag_delta(int64_t base, uint64_t zigzagged, int64_t* out) {
  const int64_t d = zigzag_decode(zigzagged), limit = int64_t(1) << 40;
  if (d > limit || d < -limit) return false;
  *out = base + d;
  return true;
}

class ByteWriter {
 public:
  void u8(uint8_t v) { buf_.push_back(v); }
  void u16(uint16_t v) { put(v, 2); }
  void u32(uint32_t v) { put(v, 4); }
  void u64(uint64_t v) { put(v, 8); }
  void f32(float v) { uint32_t b; std::memcpy(&b, &v, 4); u32(b); }
  void f64(double v) { uint64_t b; std::memcpy(&b, &v, 8); u64(b); }
  void bytes(const void* p, size_t n) {
    const uint8_t* b = static_cast<const uint8_t*>(p);
    buf_.insert(buf_.end(), b, b + n);
  }
  // Variable-length unsigned (7 bits per byte, low first); at most 10 bytes for 64 bits.
  void varint(uint64_t v) {
    while (v >= 0x80) { u8(uint8_t(v) | 0x80); v >>= 7; }
    u8(uint8_t(v));
  }
  void str(const std::string& s) { varint(s.size()); bytes(s.data(), s.size()); }
  size_t size() const { return buf_.size(); }
  std::vector<uint8_t>& data() { return buf_; }
  const std::vector<uint8_t>& data() const { return buf_; }

 private:
  void put(uint64_t v, int n) { for (int i = 0; i < n; ++i) buf_.push_back(uint8_t(v >> (8 * i))); }
  std::vector<uint8_t> buf_;
};

class ByteReader {
 public:
  ByteReader(const uint8_t* p, size_t n) : p_(p), n_(n) {}
  bool ok = true;

  uint8_t u8() { return uint8_t(get(1)); }
  uint16_t u16() { return uint16_t(get(2)); }
  uint32_t u32() { return uint32_t(get(4)); }
  uint64_t u64() { return get(8); }
  float f32() { uint32_t b = u32(); float v; std::memcpy(&v, &b, 4); return v; }
  double f64() { uint64_t b = u64(); double v; std::memcpy(&v, &b, 8); return v; }
  uint64_t varint() {
    uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      uint8_t b = u8();
      if (!ok) return 0;
      v |= uint64_t(b & 0x7f) << shift;
      if (!(b & 0x80)) return v;
    }
    ok = false;  // more than 10 bytes: malformed
    return 0;
  }
  // Returns a pointer to the next n bytes and skips them, or nullptr (and ok = false).
  const uint8_t* take(size_t n) {
    if (!ok || n > n_ - pos_) { ok = false; return nullptr; }
    const uint8_t* r = p_ + pos_;
    pos_ += n;
    return r;
  }
  std::string str(size_t max_len) {
    uint64_t n = varint();
    if (n > max_len) { ok = false; return {}; }
    const uint8_t* p = take(size_t(n));
    return p ? std::string(reinterpret_cast<const char*>(p), size_t(n)) : std::string();
  }
  size_t remaining() const { return n_ - pos_; }
  size_t position() const { return pos_; }

 private:
  uint64_t get(int n) {
    const uint8_t* p = take(size_t(n));
    if (!p) return 0;
    uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= uint64_t(p[i]) << (8 * i);
    return v;
  }
  const uint8_t* p_;
  size_t n_;
  size_t pos_ = 0;
};

}  // namespace dcurve
