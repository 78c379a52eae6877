#include "codec/common/motion_compensation.h"

namespace dcurve {

void cluster_centre(const int32_t* ref, const Traversal& t, uint32_t begin, uint32_t end, int64_t centre[3]) {
  for (int a = 0; a < 3; ++a) {
    int64_t sum = 0;
    for (uint32_t pos = begin; pos < end; ++pos) sum += ref[size_t(t.order[pos]) * 3 + size_t(a)];
    const int64_t n = int64_t(end - begin);
    centre[a] = sum >= 0 ? sum / n : -((-sum + n - 1) / n);  // floor
  }
}

}  // namespace dcurve
