// Context-adaptive coding of signed integers (residuals) with the binary range coder.
// A value is split into binary decisions: zero?, sign, exponent (unary), mantissa. The
// zero flag and exponent adapt per caller-chosen magnitude context, the sign per a separate
// sign context; mantissa bits adapt per exponent, since their statistics depend little on
// the neighbourhood. The models are shared; AdaptiveIntCoder::encode is defined on the
// writing side (codec/compress/int_encoder.cpp, with codec/compress/range_encoder.h),
// AdaptiveIntCoder::decode on the reading side (codec/decompress/int_decoder.cpp, with
// codec/decompress/range_decoder.h).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/bit_model.h"

namespace dcurve {

class RangeEncoder;
class RangeDecoder;

// Largest exponent (floor(log2|v|)) the binarization can express: |v| < 2^41, which
// covers any difference of int32 grid values and their predictions.
constexpr int kMaxExponent = 40;

// |v| as an unsigned value, exact for every int64 (INT64_MIN included).
inline uint64_t magnitude_of(int64_t v) { return v < 0 ? 0 - uint64_t(v) : uint64_t(v); }

// floor(log2(m)) for m >= 1, 0 for m = 0: a magnitude's exponent class. The encoder's rate
// estimates call it per candidate value, so it uses the count-leading-zeros instruction.
inline int floor_log2(uint64_t m) {
#if defined(__GNUC__) || defined(__clang__)
  return m ? 63 - __builtin_clzll(m) : 0;
#else
  int e = 0;
  while (m >>= 1) ++e;
  return e;
#endif
}

class AdaptiveIntCoder {
 public:
  // contexts, sign_contexts: numbers of distinct context ids callers pass, >= 1 each.
  AdaptiveIntCoder(int contexts, int sign_contexts);

  // ctx in [0, contexts), sign_ctx in [0, sign_contexts). |v| < 2^(kMaxExponent+1).
  void encode(RangeEncoder& enc, int ctx, int sign_ctx, int64_t v);
  // Returns the decoded value; a corrupted stream yields some value (the caller checks
  // ranges and the stream's checksum), never an out-of-bounds access.
  int64_t decode(RangeDecoder& dec, int ctx, int sign_ctx);

 private:
  struct Context {
    BitModel zero;
    std::array<BitModel, kMaxExponent> exponent;  // "exponent > i" decisions
  };
  struct Mantissa {
    std::array<BitModel, 3> top;  // first two bits below the leading one, as a 2-level tree
    BitModel rest;
  };
  std::vector<Context> ctx_;
  std::vector<BitModel> sign_;
  std::array<Mantissa, kMaxExponent + 1> mant_;
};

// What AdaptiveIntCoder::encode and ::decode share beyond the models.
namespace int_coder_detail {
// Bit position i (counted from the top, 0-based) of the e mantissa bits uses the tree
// model for the first two bits and one shared model below.
template <class Coder, class Op>
uint64_t walk_mantissa(Coder& coder, std::array<BitModel, 3>& top, BitModel& rest, int e, Op op) {
  uint64_t bits = 0;
  for (int i = 0; i < e; ++i) {
    BitModel& m = i == 0 ? top[0] : i == 1 ? top[1 + (bits & 1)] : rest;
    bits = (bits << 1) | uint64_t(op(coder, m, e - 1 - i));
  }
  return bits;
}
}  // namespace int_coder_detail

}  // namespace dcurve
