#include "codec/int_coder.h"

namespace dcurve {
namespace {
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
}  // namespace

AdaptiveIntCoder::AdaptiveIntCoder(int contexts, int sign_contexts)
    : ctx_(size_t(contexts < 1 ? 1 : contexts)), sign_(size_t(sign_contexts < 1 ? 1 : sign_contexts)) {}

void AdaptiveIntCoder::encode(RangeEncoder& enc, int ctx, int sign_ctx, int64_t v) {
  Context& c = ctx_[size_t(ctx)];
  enc.encode(c.zero, v == 0);
  if (v == 0) return;
  enc.encode(sign_[size_t(sign_ctx)], v < 0);
  const uint64_t m = magnitude_of(v);
  const int e = floor_log2(m);
  for (int i = 0; i < e; ++i) enc.encode(c.exponent[size_t(i)], 1);
  if (e < kMaxExponent) enc.encode(c.exponent[size_t(e)], 0);
  Mantissa& mt = mant_[size_t(e)];
  walk_mantissa(enc, mt.top, mt.rest, e, [m](RangeEncoder& en, BitModel& b, int pos) {
    const int bit = int((m >> pos) & 1);
    en.encode(b, bit);
    return bit;
  });
}

int64_t AdaptiveIntCoder::decode(RangeDecoder& dec, int ctx, int sign_ctx) {
  Context& c = ctx_[size_t(ctx)];
  if (dec.decode(c.zero)) return 0;
  const bool negative = dec.decode(sign_[size_t(sign_ctx)]);
  int e = 0;
  while (e < kMaxExponent && dec.decode(c.exponent[size_t(e)])) ++e;
  Mantissa& mt = mant_[size_t(e)];
  const uint64_t low = walk_mantissa(dec, mt.top, mt.rest, e,
                                     [](RangeDecoder& de, BitModel& b, int) { return de.decode(b); });
  const int64_t m = int64_t((uint64_t(1) << e) | low);
  return negative ? -m : m;
}

}  // namespace dcurve
