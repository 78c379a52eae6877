// The reading half of the adaptive binary range coder (codec/common/bit_model.h): decodes
// what codec/compress/range_encoder.h wrote.
#pragma once
#include <cstddef>
#include <cstdint>

#include "codec/common/bit_model.h"

namespace dcurve {

// Reads what RangeEncoder wrote. Reading past the end yields zero bytes and marks the
// stream overrun, so a truncated or corrupted stream can never read outside its buffer.
class RangeDecoder {
 public:
  RangeDecoder(const uint8_t* data, size_t size);
  int decode(BitModel& m);
  // True when the decoder needed more bytes than the stream holds.
  bool overrun() const { return overrun_; }
  // Bytes of the stream read so far (including the look-ahead of the code register).
  size_t position() const { return pos_; }
  // After the last symbol of an intact stream: every byte read, and the code register
  // equal to the encoder's final low (the flush writes it out exactly), so corruption of
  // the tail is caught too.
  bool at_clean_end() const { return !overrun_ && pos_ == size_ && code_ == 0; }

 private:
  uint8_t next_byte();
  const uint8_t* data_;
  size_t size_, pos_ = 0;
  uint32_t range_ = 0xFFFFFFFFu, code_ = 0;
  bool overrun_ = false;
};

inline uint8_t RangeDecoder::next_byte() {
  if (pos_ < size_) return data_[pos_++];
  overrun_ = true;
  return 0;
}

inline int RangeDecoder::decode(BitModel& m) {
  const uint32_t bound = (range_ >> kProbBits) * m.p0();
  int bit;
  if (code_ < bound) {
    range_ = bound;
    bit = 0;
  } else {
    code_ -= bound;
    range_ -= bound;
    bit = 1;
  }
  m.update(bit);
  while (range_ < (1u << 24)) {
    range_ <<= 8;
    code_ = (code_ << 8) | next_byte();
  }
  return bit;
}

}  // namespace dcurve
