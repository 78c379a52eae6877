// A chunk's predictor table is a sequence of byte records, one per frame, that mostly repeat
// the previous frame's. Each byte is coded with the range coder as "equal to the byte at the
// same place of the previous record" or, failing that, its eight bits on a bit tree: a
// repeated record costs a few hundredths of a bit per byte (format_spec/residual.md, "Chunk").
// The models both sides adapt; codec/compress/record_writer.h writes records,
// codec/decompress/record_reader.h reads them.
#pragma once
#include <array>
#include <cstddef>

#include "codec/common/bit_model.h"

namespace dcurve {

struct RecordModels {
  static constexpr size_t kSlots = 8;  // places 0..6 of a record, then one for the rest
  std::array<BitModel, kSlots> same;
  std::array<BitModel, 256> tree;  // node 1..255
  static size_t slot(size_t j) { return j < kSlots - 1 ? j : kSlots - 1; }
};

}  // namespace dcurve
