#include "encoder/rate/grid.h"

#include <algorithm>
#include <cmath>

namespace dcurve {

ResidualLayer make_grid(const Animation& anim, double max_distance) {
  ResidualLayer r;
  r.step = 2.0 * max_distance / std::sqrt(3.0) * (1.0 - 1e-3);
  for (int a = 0; a < 3; ++a) {
    double lo = anim.frames[0][a];
    for (const auto& fr : anim.frames)
      for (size_t i = a; i < fr.size(); i += 3) lo = std::min(lo, double(fr[i]));
    r.origin[a] = lo;
  }
  return r;
}

bool quantize_to_grid(const Animation& anim, const ResidualLayer& grid, std::vector<int32_t>* q,
                      std::string* error) {
  const size_t n = size_t(anim.vertex_count) * 3;
  q->resize(anim.frames.size() * n);
  for (size_t f = 0; f < anim.frames.size(); ++f)
    for (size_t i = 0; i < n; ++i) {
      double g = std::nearbyint((double(anim.frames[f][i]) - grid.origin[i % 3]) / grid.step);
      if (!(g >= 0 && g <= double(INT32_MAX) / 2)) {
        if (error) *error = "tolerance too small for the motion's range (grid values overflow)";
        return false;
      }
      (*q)[f * n + i] = int32_t(g);
    }
  return true;
}

}  // namespace dcurve
