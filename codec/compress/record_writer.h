// Writes a chunk's predictor table as range-coded byte records (codec/common/record_models.h,
// format_spec/residual.md, "Chunk"); codec/decompress/record_reader.h reads them back.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/record_models.h"
#include "codec/compress/range_encoder.h"

namespace dcurve {

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

}  // namespace dcurve
