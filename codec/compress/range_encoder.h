// The writing half of the adaptive binary range coder (codec/common/bit_model.h): 32-bit
// range, 12-bit coding probabilities, carry handled with a cached byte and a run of 0xFF.
// codec/decompress/range_decoder.h reads what it writes.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/bit_model.h"

namespace dcurve {

class RangeEncoder {
 public:
  void encode(BitModel& m, int bit);
  // Appends the final bytes; call once, then take the output.
  std::vector<uint8_t>& finish();

 private:
  void shift_low();
  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
  std::vector<uint8_t> out_;
};

inline void RangeEncoder::encode(BitModel& m, int bit) {
  const uint32_t bound = (range_ >> kProbBits) * m.p0();
  if (bit == 0) {
    range_ = bound;
  } else {
    low_ += bound;
    range_ -= bound;
  }
  m.update(bit);
  while (range_ < (1u << 24)) {
    range_ <<= 8;
    shift_low();
  }
}

}  // namespace dcurve
