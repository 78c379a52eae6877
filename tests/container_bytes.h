// A second, independent reading of the .dcrv layout (format_spec/dcrv.md) for tests: split a
// file into its sections and reassemble one with valid checksums, so tests can build files a
// writer never would (unknown sections, flags, versions, absurd counts).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/bytes.h"
#include "codec/common/crc32.h"
#include "codec/compress/record_writer.h"

namespace dcurve::testing {

struct RawSection {
  std::string tag;
  uint16_t flags = 0;
  std::vector<uint8_t> stored;
  uint64_t raw_size = 0;
};

struct RawFile {
  uint16_t major = 0, minor = 0;
  uint32_t flags = 0;
  std::vector<RawSection> sections;
  std::vector<uint8_t> chunk_data;  // the bytes after the sections (the residual chunks)
};

inline RawFile split_file(const std::vector<uint8_t>& bytes) {
  RawFile f;
  ByteReader r(bytes.data(), bytes.size());
  r.take(4);
  f.major = r.u16();
  f.minor = r.u16();
  f.flags = r.u32();
  const uint32_t count = r.u32();
  const uint64_t head = r.u64();
  r.u32();
  for (uint32_t i = 0; i < count && r.ok; ++i) {
    RawSection s;
    const uint8_t* tag = r.take(4);
    if (!tag) break;
    s.tag.assign(reinterpret_cast<const char*>(tag), 4);
    s.flags = r.u8();
    const uint64_t stored = r.varint();
    s.raw_size = s.flags & 2 ? r.varint() : stored;
    r.u32();
    const uint8_t* p = r.take(size_t(stored));
    if (p) s.stored.assign(p, p + stored);
    f.sections.push_back(s);
  }
  if (head <= bytes.size()) f.chunk_data.assign(bytes.begin() + std::ptrdiff_t(head), bytes.end());
  return f;
}

inline std::vector<uint8_t> assemble(const RawFile& f) {
  ByteWriter body;
  for (const RawSection& s : f.sections) {
    size_t at = body.size();
    body.bytes(s.tag.data(), 4);
    body.u8(uint8_t(s.flags));
    body.varint(s.stored.size());
    if (s.flags & 2) body.varint(s.raw_size);
    body.u32(crc32c(s.stored.data(), s.stored.size(), crc32c(body.data().data() + at, body.size() - at)));
    body.bytes(s.stored.data(), s.stored.size());
  }
  ByteWriter w;
  w.bytes("DCRV", 4);
  w.u16(f.major);
  w.u16(f.minor);
  w.u32(f.flags);
  w.u32(uint32_t(f.sections.size()));
  w.u64(28 + body.size());
  w.u32(crc32c(w.data().data(), 24));
  w.bytes(body.data().data(), body.size());
  w.bytes(f.chunk_data.data(), f.chunk_data.size());
  return std::move(w.data());
}

// An uncompressed section holding `raw`.
inline RawSection plain_section(const std::string& tag, bool required, const std::vector<uint8_t>& raw) {
  return {tag, uint16_t(required ? 1 : 0), raw, raw.size()};
}

// The chunk index of a residual payload (format_spec/residual.md), read independently of
// codec/decompress/residual_decoder.cpp: where each chunk starts in the payload, its size and where its CRC sits.
struct PayloadChunk {
  size_t start = 0, size = 0, crc_at = 0;
};
inline std::vector<PayloadChunk> payload_chunks(const std::vector<uint8_t>& p) {
  ByteReader r(p.data(), p.size());
  r.u8();
  r.u8();
  r.varint();
  const uint64_t count = r.varint();
  std::vector<PayloadChunk> chunks;
  for (uint64_t c = 0; c < count && r.ok; ++c) {
    PayloadChunk e;
    e.start = size_t(r.varint());
    e.size = size_t(r.varint());
    e.crc_at = r.position();
    r.u32();
    chunks.push_back(e);
  }
  for (PayloadChunk& e : chunks) e.start += r.position();
  return chunks;
}

// Sets byte `at` of chunk `c` (counted from the chunk's start, past its values checksum)
// and fixes the chunk's CRC, so the edit reaches the chunk's parser.
inline void set_chunk_byte(std::vector<uint8_t>* p, size_t c, size_t at, uint8_t value) {
  const PayloadChunk e = payload_chunks(*p)[c];
  (*p)[e.start + 4 + at] = value;
  const uint32_t crc = crc32c(p->data() + e.start, e.size);
  for (int b = 0; b < 4; ++b) (*p)[e.crc_at + size_t(b)] = uint8_t(crc >> (8 * b));
}
inline uint8_t chunk_byte(const std::vector<uint8_t>& p, size_t c, size_t at) {
  return p[payload_chunks(p)[c].start + 4 + at];
}

// A residual payload of one chunk of `frames` frames whose predictor table is `records`
// (format_spec/residual.md: the cluster size and motion block, then one record per frame)
// and nothing after it: what no writer writes, for the decoder's rules on the table.
inline std::vector<uint8_t> table_payload(uint32_t frames, bool faces, const std::vector<std::vector<uint8_t>>& records) {
  RangeEncoder enc;
  RecordWriter table(enc);
  for (const std::vector<uint8_t>& r : records) table.record(r);
  ByteWriter chunk;
  chunk.u32(0);  // values checksum: never reached
  const std::vector<uint8_t>& stream = enc.finish();
  chunk.bytes(stream.data(), stream.size());
  ByteWriter w;
  w.u8(3);
  w.u8(faces ? 1 : 0);
  w.varint(frames);
  w.varint(1);
  w.varint(0);
  w.varint(chunk.size());
  w.u32(crc32c(chunk.data().data(), chunk.size()));
  w.bytes(chunk.data().data(), chunk.size());
  return std::move(w.data());
}

// Predictor bytes of the table: kind | spatial << 4.
inline uint8_t predictor_byte(int kind, int spatial) { return uint8_t(kind | spatial << 4); }

}  // namespace dcurve::testing
