#include "encoder/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dcurve {

double bbox_diagonal(const std::vector<float>& xyz) {
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) { lo[a] = std::numeric_limits<double>::infinity(); hi[a] = -lo[a]; }
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], double(xyz[i]));
    hi[i % 3] = std::max(hi[i % 3], double(xyz[i]));
  }
  if (xyz.empty()) return 0;
  double d2 = 0;
  for (int a = 0; a < 3; ++a) d2 += (hi[a] - lo[a]) * (hi[a] - lo[a]);
  return std::sqrt(d2);
}

ErrorStats measure_error(const Animation& ref, const std::vector<std::vector<float>>& decoded) {
  ErrorStats s;
  const double L = bbox_diagonal(ref.frames.at(0));
  const size_t V = ref.vertex_count;
  double sum2 = 0, spread2 = 0;
  for (size_t f = 0; f < ref.frames.size(); ++f) {
    const auto& x = ref.frames[f];
    const auto& y = decoded.at(f);
    double c[3] = {0, 0, 0};
    for (size_t v = 0; v < V; ++v)
      for (int a = 0; a < 3; ++a) c[a] += x[3 * v + a];
    for (double& ca : c) ca /= double(V);
    double frame_max = 0;
    for (size_t v = 0; v < V; ++v) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) {
        double d = double(y[3 * v + a]) - double(x[3 * v + a]);
        d2 += d * d;
        double e = double(x[3 * v + a]) - c[a];
        spread2 += e * e;
      }
      sum2 += d2;
      frame_max = std::max(frame_max, d2);
    }
    s.max_error_per_frame.push_back(std::sqrt(frame_max) / L);
    s.max_error = std::max(s.max_error, s.max_error_per_frame.back());
  }
  s.rmse = std::sqrt(sum2 / double(V * ref.frames.size())) / L;
  s.kg_error_pct = spread2 > 0 ? 100.0 * std::sqrt(sum2 / spread2) : 0.0;
  return s;
}

}  // namespace dcurve
