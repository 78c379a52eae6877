#include "codec/decompress/range_decoder.h"

namespace dcurve {

RangeDecoder::RangeDecoder(const uint8_t* data, size_t size) : data_(data), size_(size) {
  // The encoder's first output byte is the initial cache (always 0); the code register
  // takes the next four.
  for (int i = 0; i < 5; ++i) code_ = (code_ << 8) | next_byte();
}

}  // namespace dcurve
