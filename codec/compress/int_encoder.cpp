// AdaptiveIntCoder's writing half (codec/common/int_coder.h).
#include "codec/common/int_coder.h"
#include "codec/compress/range_encoder.h"

namespace dcurve {

using int_coder_detail::walk_mantissa;

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

}  // namespace dcurve
