// AdaptiveIntCoder's reading half (codec/common/int_coder.h).
#include "codec/common/int_coder.h"
#include "codec/decompress/range_decoder.h"

namespace dcurve {

using int_coder_detail::walk_mantissa;

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
