// Adaptive binary range coder: the entropy coder of the residual layer. Each binary
// decision is coded with a probability that adapts to what was coded before in the same
// context, so skewed, slowly changing residual statistics cost close to their entropy.
// This header is the probability model both halves adapt identically; the coder itself is
// codec/compress/range_encoder.h (writing) and codec/decompress/range_decoder.h (reading).
#pragma once
#include <cstdint>

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

}  // namespace dcurve
