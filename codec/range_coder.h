// Adaptive binary range coder: the entropy coder of the residual layer. Each binary
// decision is coded with a probability that adapts to what was coded before in the same
// context, so skewed, slowly changing residual statistics cost close to their entropy.
// 32-bit range, 12-bit coding probabilities, carry handled with a cached byte and a run of 0xFF.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dcurve {

// Probability that the next bit in this context is 0, kept at two adaptation speeds
// (fast follows local changes, slow gives precision on stationary statistics); their
// mean, in 1/4096 units, codes the bit. Both start at one half.
struct BitModel {
  uint16_t fast = 1u << 15, slow = 1u << 15;  // 1/65536 units
  uint32_t p0() const { return ((uint32_t(fast) + slow) >> 5) | 1u; }  // in [1, 4095]
  void update(int bit) {
    if (bit == 0) {
      fast = uint16_t(fast + ((65536u - fast) >> kFastShift));
      slow = uint16_t(slow + ((65536u - slow) >> kSlowShift));
    } else {
      fast = uint16_t(fast - (fast >> kFastShift));
      slow = uint16_t(slow - (slow >> kSlowShift));
    }
  }
  static constexpr int kFastShift = 4, kSlowShift = 7;
};

constexpr int kProbBits = 12;

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
