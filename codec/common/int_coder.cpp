#include "codec/common/int_coder.h"

namespace dcurve {

AdaptiveIntCoder::AdaptiveIntCoder(int contexts, int sign_contexts)
    : ctx_(size_t(contexts < 1 ? 1 : contexts)), sign_(size_t(sign_contexts < 1 ? 1 : sign_contexts)) {}

}  // namespace dcurve
