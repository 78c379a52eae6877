// Reads a chunk's predictor table from its range-coded byte records
// (codec/common/record_models.h, format_spec/residual.md, "Chunk"), as
// codec/compress/record_writer.h wrote them.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/record_models.h"
#include "codec/decompress/range_decoder.h"

namespace dcurve {

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
