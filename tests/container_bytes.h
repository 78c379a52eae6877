// A second, independent reading of the .dcrv layout (format_spec/dcrv.md) for tests: split a
// file into its sections and reassemble one with valid checksums, so tests can build files a
// writer never would (unknown sections, flags, versions, absurd counts).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/bytes.h"
#include "codec/crc32.h"

namespace dcurve::testing {

struct RawSection {
  std::string tag;
  uint16_t flags = 0;
  std::vector<uint8_t> stored;
  uint64_t raw_size = 0;
};

struct RawFile {
  uint16_t major = 0, minor = 0;
  uint32_t flags = 0;  // bit 0: compact section headers
  std::vector<RawSection> sections;
};

constexpr uint32_t kCompactSections = 1;

inline RawFile split_file(const std::vector<uint8_t>& bytes) {
  RawFile f;
  ByteReader r(bytes.data(), bytes.size());
  r.take(4);
  f.major = r.u16();
  f.minor = r.u16();
  f.flags = r.u32();
  uint32_t count = r.u32();
  r.u32();
  for (uint32_t i = 0; i < count && r.ok; ++i) {
    RawSection s;
    const uint8_t* tag = r.take(4);
    if (!tag) break;
    s.tag.assign(reinterpret_cast<const char*>(tag), 4);
    uint64_t stored = 0;
    if (f.flags & kCompactSections) {
      s.flags = r.u8();
      stored = r.varint();
      s.raw_size = s.flags & 2 ? r.varint() : stored;
    } else {
      s.flags = r.u16();
      r.u16();
      stored = r.u64();
      s.raw_size = r.u64();
    }
    r.u32();
    const uint8_t* p = r.take(size_t(stored));
    if (p) s.stored.assign(p, p + stored);
    f.sections.push_back(s);
  }
  return f;
}

inline std::vector<uint8_t> assemble(const RawFile& f) {
  ByteWriter w;
  w.bytes("DCRV", 4);
  w.u16(f.major);
  w.u16(f.minor);
  w.u32(f.flags);
  w.u32(uint32_t(f.sections.size()));
  w.u32(crc32c(w.data().data(), 16));
  for (const RawSection& s : f.sections) {
    size_t at = w.size();
    w.bytes(s.tag.data(), 4);
    if (f.flags & kCompactSections) {
      w.u8(uint8_t(s.flags));
      w.varint(s.stored.size());
      if (s.flags & 2) w.varint(s.raw_size);
    } else {
      w.u16(s.flags);
      w.u16(0);
      w.u64(s.stored.size());
      w.u64(s.raw_size);
    }
    w.u32(crc32c(s.stored.data(), s.stored.size(), crc32c(w.data().data() + at, w.size() - at)));
    w.bytes(s.stored.data(), s.stored.size());
  }
  return std::move(w.data());
}

// An uncompressed section holding `raw`.
inline RawSection plain_section(const std::string& tag, bool required, const std::vector<uint8_t>& raw) {
  return {tag, uint16_t(required ? 1 : 0), raw, raw.size()};
}

}  // namespace dcurve::testing
