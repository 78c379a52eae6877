// Context-adaptive coding of signed integers (residuals) with the binary range coder.
// A value is split into binary decisions: zero?, sign, exponent (unary), mantissa. The
// zero flag and exponent adapt per caller-chosen magnitude context, the sign per a separate
// sign context; mantissa bits adapt per exponent, since their statistics depend little on
// the neighbourhood.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "codec/range_coder.h"

namespace dcurve {

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

}  // namespace dcurve
