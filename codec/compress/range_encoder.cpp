#include "codec/compress/range_encoder.h"

namespace dcurve {

// A byte leaves the encoder only once no later carry can change it: bytes equal to 0xFF
// are held back (counted in cache_size_) until the carry into them is known.
void RangeEncoder::shift_low() {
  if (uint32_t(low_) < 0xFF000000u || (low_ >> 32) != 0) {
    const uint8_t carry = uint8_t(low_ >> 32);
    uint8_t held = cache_;
    do {
      out_.push_back(uint8_t(held + carry));
      held = 0xFF;
    } while (--cache_size_ != 0);
    cache_ = uint8_t(low_ >> 24);
  }
  ++cache_size_;
  low_ = (low_ & 0x00FFFFFFu) << 8;
}

std::vector<uint8_t>& RangeEncoder::finish() {
  for (int i = 0; i < 5; ++i) shift_low();
  return out_;
}

}  // namespace dcurve
