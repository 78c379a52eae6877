// A chunk's predictor table is a sequence of byte records, one per frame, that mostly repeat
// the previous frame's. Each byte is coded with the range coder as "equal to the byte at the
// same place of the previous record" or, failing that, its eight bits on a bit tree: a
// repeated record costs a few hundredths of a bit per byte (format_spec/residual.md, "Chunk").
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/range_coder.h"

namespace dcurve {

struct RecordModels {
  static constexpr size_t kSlots = 8;  // places 0..6 of a record, then one for the rest
  std::array<BitModel, kSlots> same;
  std::array<BitModel, 256> tree;  // node 1..255
  static size_t slot(size_t j) { return j < kSlots - 1 ? j : kSlots - 1; }
};

class RecordWriter {
 public:
  explicit RecordWriter(RangeEncoder& enc) : enc_(enc) {}
  void record(const std::vector<uint8_t>& bytes) {
    for (size_t j = 0; j < bytes.size(); ++j) {
      if (j < previous_.size()) {
        const int same = bytes[j] == previous_[j];
        enc_.encode(m_.same[RecordModels::slot(j)], same);
        if (same) continue;
      }
      for (int b = 7, node = 1; b >= 0; --b) {
        const int bit = bytes[j] >> b & 1;
        enc_.encode(m_.tree[size_t(node)], bit);
        node = 2 * node + bit;
      }
    }
    previous_ = bytes;
  }

 private:
  RangeEncoder& enc_;
  RecordModels m_;
  std::vector<uint8_t> previous_;
};

// Reads what RecordWriter wrote, field by field, with ByteReader's interface: every read
// either succeeds or sets ok = false (the stream overran) and returns zero.
class RecordReader {
 public:
  explicit RecordReader(RangeDecoder& dec) : dec_(dec) {}
  bool ok = true;
  uint8_t u8() {
    const size_t j = current_.size();
    uint8_t byte = 0;
    if (j < previous_.size() && dec_.decode(m_.same[RecordModels::slot(j)])) {
      byte = previous_[j];
    } else {
      int node = 1;
      for (int b = 0; b < 8; ++b) node = 2 * node + dec_.decode(m_.tree[size_t(node)]);
      byte = uint8_t(node - 256);
    }
    if (dec_.overrun()) ok = false;
    current_.push_back(byte);
    return ok ? byte : 0;
  }
  uint64_t varint() {
    uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      const uint8_t b = u8();
      if (!ok) return 0;
      v |= uint64_t(b & 0x7f) << shift;
      if (!(b & 0x80)) return v;
    }
    ok = false;  // more than 10 bytes: malformed
    return 0;
  }
  // The record ends: the next one is compared with it.
  void end_record() {
    previous_.swap(current_);
    current_.clear();
  }

 private:
  RangeDecoder& dec_;
  RecordModels m_;
  std::vector<uint8_t> previous_, current_;
};

}  // namespace dcurve
