#include "codec/common/fast_residual.h"

#include <algorithm>

namespace dcurve {
namespace fast_residual {
// One loop per kind, each a plain pass the compiler vectorises.
void predict_frame(FrameKind kind, const int32_t* q1, const int32_t* q2, const int32_t* M, const int32_t* M1,
                   size_t n, int32_t* out) {
  switch (kind) {
    case FrameKind::Previous:
      std::copy(q1, q1 + n, out);
      return;
    case FrameKind::Linear:
      for (size_t i = 0; i < n; ++i) out[i] = clamp_int32(2 * int64_t(q1[i]) - q2[i]);
      return;
    case FrameKind::Model:
      std::copy(M, M + n, out);
      return;
    case FrameKind::ModelDelta:
      for (size_t i = 0; i < n; ++i) out[i] = clamp_int32(int64_t(M[i]) + q1[i] - M1[i]);
      return;
    case FrameKind::None:
      std::fill(out, out + n, 0);
      return;
  }
}

}  // namespace fast_residual
}  // namespace dcurve
